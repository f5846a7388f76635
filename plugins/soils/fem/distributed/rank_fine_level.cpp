#include "distributed/rank_fine_level.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "distributed/rank_agreement.hpp"

namespace rumble::fem {

namespace {

/// The diagonal of K + S on the owned DOFs of rows, from op's part of K (a shared node's
/// diagonal summed over the ranks that hold pieces of it), 1 on held DOFs.
Eigen::VectorXd owned_diagonal(const MeshPartition& part, const SoilOperator& op,
                               const RankRows& rows) {
  Eigen::VectorXd d = op.stiffness_diagonal();
  part.halo->sum_to_roots(d.data(), d.data(), 3);
  for (const BoundaryNode& b : op.boundary())  // (each copy holds the node's whole block)
    for (int c = 0; c < 3; ++c) d[3 * b.node + c] += b.spring(c, c);
  Eigen::VectorXd owned(3 * static_cast<Eigen::Index>(rows.owned.size()));
  for (std::size_t k = 0; k < rows.owned.size(); ++k)
    for (int c = 0; c < 3; ++c)
      owned[3 * k + c] = op.fixed()[rows.owned[k]] ? 1.0 : d[3 * rows.owned[k] + c];
  return owned;
}

}  // namespace

RankFineLevel::RankFineLevel(const MeshPartition& part_, const SoilOperator& op_, MPI_Comm comm_)
    : comm(comm_), part(&part_), op(&op_) {
  // Nothing here reads K's rows: they are about 0.5 kB per DOF of the part (12 B a nonzero),
  // 29 % of a rank's peak at 9.3e5 DOFs when they were kept (docs/fem-soil.md §8).
  op->release_stiffness();
  rows = number_rows(*part, comm);
  fixed = op->fixed();
  diagonal = owned_diagonal(*part, *op, rows);
  const auto n = 3 * static_cast<PetscInt>(rows.owned.size());
  in = Eigen::VectorXd::Zero(op->dofs());
  out = Eigen::VectorXd::Zero(op->dofs());
  const auto shell = [this, n](Mat& m, PetscErrorCode (*product)(Mat, Vec, Vec)) {
    petsc_check(MatCreateShell(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, this, &m),
                "MatCreateShell");
    petsc_check(MatShellSetOperation(m, MATOP_MULT, reinterpret_cast<void (*)(void)>(product)),
                "MatShellSetOperation");
    petsc_check(MatShellSetOperation(m, MATOP_GET_DIAGONAL,
                                     reinterpret_cast<void (*)(void)>(&get_diagonal)),
                "MatShellSetOperation");
    petsc_check(MatSetBlockSize(m, 3), "MatSetBlockSize");
    petsc_check(MatSetOption(m, MAT_SPD, PETSC_TRUE), "MatSetOption");
  };
  shell(fine, &multiply<false>);
  shell(smoothed, &multiply<true>);
  petsc_check(MatCreateVecs(fine, &x, &b), "MatCreateVecs");
  petsc_check(VecSet(x, 0.0), "VecSet");
}

RankFineLevel::~RankFineLevel() {
  VecDestroy(&x);
  VecDestroy(&b);
  MatDestroy(&smoothed);
  MatDestroy(&fine);
}

template <bool kStepped>
PetscErrorCode RankFineLevel::multiply(Mat a, Vec x, Vec y) {
  RankFineLevel* p = nullptr;
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(MatShellGetContext(a, &p));
  const std::vector<std::int32_t>& owned = p->rows.owned;
  PetscCall(VecGetArrayRead(x, &in));
  for (std::size_t k = 0; k < owned.size(); ++k)
    for (int c = 0; c < 3; ++c) p->in[3 * owned[k] + c] = p->fixed[owned[k]] ? 0.0 : in[3 * k + c];
  try {  // (a C++ exception must not cross PETSc's C frames)
    p->part->halo->to_leaves(p->in.data(), p->in.data(), 3);  // (the ghosts: their owners')
    if constexpr (kStepped)
      p->op->stepped_stiffness_times(p->in, p->out, true);
    else
      p->op->stiffness_times(p->in, p->out, true);
  } catch (...) {
    if (!p->stop.failed) p->stop.failed = std::current_exception();
  }
  PetscCall(VecGetArray(y, &out));
  for (std::size_t k = 0; k < owned.size(); ++k)
    for (int c = 0; c < 3; ++c)
      out[3 * k + c] =
          p->fixed[owned[k]] || p->stop.failed ? in[3 * k + c] : p->out[3 * owned[k] + c];
  PetscCall(VecRestoreArray(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  return 0;
}

template PetscErrorCode RankFineLevel::multiply<false>(Mat, Vec, Vec);
template PetscErrorCode RankFineLevel::multiply<true>(Mat, Vec, Vec);

PetscErrorCode RankFineLevel::get_diagonal(Mat a, Vec d) {
  RankFineLevel* p = nullptr;
  PetscCall(MatShellGetContext(a, &p));
  return copy_into(p->diagonal, d);
}

KSP RankFineLevel::two_level_cg(Mat coarse, Mat interpolation, double& tolerance, int& levels,
                                const char* what) {
  KSP ksp = static_cg(comm, fine, fine, tolerance);
  set_two_level_multigrid(ksp, smoothed, coarse, interpolation);
  petsc_check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  PetscReal asked = tolerance;  // (PETSC_OPTIONS' -fem_statics_ksp_rtol, if given, for the log)
  petsc_check(KSPGetTolerances(ksp, &asked, nullptr, nullptr, nullptr), "KSPGetTolerances");
  tolerance = asked;
  PetscErrorCode code = 0;
  {
    const SetUpOptions options;  // (GAMG's products on the coarse MPIAIJ matrix)
    code = KSPSetUp(ksp);
  }
  agree(comm, std::exchange(stop.failed, nullptr));  // (the smoothers' estimates' products)
  petsc_check(code, (std::string("KSPSetUp (the ") + what + "'s levels on the ranks)").c_str());
  levels = two_level_multigrid_levels(ksp);
  return ksp;
}

}  // namespace rumble::fem
