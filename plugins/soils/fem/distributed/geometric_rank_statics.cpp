#include "distributed/geometric_rank_statics.hpp"

#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "distributed/rank_agreement.hpp"
#include "distributed/rank_petsc.hpp"
#include "statics/nested_interpolation.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"
#include "statics/two_level_multigrid.hpp"

namespace rumble::fem {

struct GeometricRankStatics::Petsc {
  ~Petsc() {  // (errors ignored: a destructor)
    KSPDestroy(&ksp);
    VecDestroy(&x);
    VecDestroy(&b);
    MatDestroy(&interpolation);
    MatDestroy(&node_interpolation);
    MatDestroy(&coarse);
    MatDestroy(&smoothed);
    MatDestroy(&fine);
  }
  /// y = (K + S) x over the ranks by the operator's product, K in double (kStepped false: CG's
  /// operator) or as the step reads it (true: the smoother's); identity rows and columns on held
  /// DOFs (x's held entries taken out first: the shell is symmetric for any x, as the smoother's
  /// estimate of the spectrum needs, statics/geometric_static_solver.cpp).
  /// The fine level's MATOP_MULT, collective as MatMult is. A failed product (it still made its
  /// exchanges, distributed_operator.hpp) is kept in `stop.failed` and gives y = x: a PETSc error
  /// here would end MatMult on this rank alone while the others wait in CG's next sum; CG ends
  /// at the next iteration on every rank instead and the ranks agree on the failure.
  template <bool kStepped>
  static PetscErrorCode multiply(Mat a, Vec x, Vec y) {
    Petsc* p = nullptr;
    const PetscScalar* in = nullptr;
    PetscScalar* out = nullptr;
    PetscCall(MatShellGetContext(a, &p));
    const std::vector<std::int32_t>& owned = p->rows.owned;
    PetscCall(VecGetArrayRead(x, &in));
    for (std::size_t k = 0; k < owned.size(); ++k)
      for (int c = 0; c < 3; ++c)
        p->in[3 * owned[k] + c] = p->fixed[owned[k]] ? 0.0 : in[3 * k + c];
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
  /// The diagonal of K + S on the owned DOFs (1 on held ones): MATOP_GET_DIAGONAL, for Jacobi.
  static PetscErrorCode get_diagonal(Mat a, Vec d) {
    Petsc* p = nullptr;
    PetscScalar* out = nullptr;
    PetscCall(MatShellGetContext(a, &p));
    PetscCall(VecGetArray(d, &out));
    std::copy(p->diagonal.data(), p->diagonal.data() + p->diagonal.size(), out);
    PetscCall(VecRestoreArray(d, &out));
    return 0;
  }
  std::shared_ptr<PetscSession> session = PetscSession::get();
  MPI_Comm comm = MPI_COMM_NULL;
  const MeshPartition* part = nullptr;
  const SoilOperator* op = nullptr;
  RankRows rows;
  std::vector<char> fixed;                                   // per local node: held
  Eigen::VectorXd diagonal;                                  // per owned DOF
  Eigen::VectorXd in, out;                                   // per local DOF, the shell's
  Mat fine = nullptr, smoothed = nullptr, coarse = nullptr;  // smoothed: K as the step reads it
  Mat node_interpolation = nullptr;                          // owned fine nodes x coarse nodes
  Mat interpolation = nullptr;   // the same on each of a node's 3 DOFs (MAIJ)
  Vec x = nullptr, b = nullptr;  // x: the last solution (CG's start)
  KSP ksp = nullptr;
  PetscStopTest stop;
};

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

GeometricRankStatics::GeometricRankStatics(const MeshPartition& fine, const SoilOperator& op,
                                           const MeshPartition& coarse,
                                           const SoilOperator& coarse_op, int levels, MPI_Comm comm,
                                           double tolerance)
    : part_(fine), petsc_(std::make_unique<Petsc>()), tolerance_(tolerance) {
  const auto start = std::chrono::steady_clock::now();
  Petsc& p = *petsc_;
  p.comm = comm;
  p.part = &fine;
  p.op = &op;
  // Nothing here reads K's rows: CG's product in double forms K from the part's tetrahedra
  // (distributed_operator.hpp), and the rows are about 0.5 kB per DOF of the part (12 B a
  // nonzero), 29 % of a rank's peak at 9.3e5 DOFs when they were kept (docs/fem-soil.md §8).
  op.release_stiffness();
  p.rows = number_rows(fine, comm);
  p.fixed = op.fixed();
  p.diagonal = owned_diagonal(fine, op, p.rows);
  make_fine_level();
  make_interpolation(coarse, coarse_op, levels);
  build_solver(coarse, coarse_op);
  set_stop_test(p.ksp, op, p.stop);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

GeometricRankStatics::~GeometricRankStatics() = default;

void GeometricRankStatics::set_stop_check(std::function<void()> check) {
  petsc_->stop.check = std::move(check);
}

void GeometricRankStatics::make_fine_level() {
  Petsc& p = *petsc_;
  const auto n = 3 * static_cast<PetscInt>(p.rows.owned.size());
  p.in = Eigen::VectorXd::Zero(p.op->dofs());
  p.out = Eigen::VectorXd::Zero(p.op->dofs());
  const auto shell = [&p, n](Mat& m, PetscErrorCode (*multiply)(Mat, Vec, Vec)) {
    petsc_check(MatCreateShell(p.comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, &p, &m),
                "MatCreateShell");
    petsc_check(MatShellSetOperation(m, MATOP_MULT, reinterpret_cast<void (*)(void)>(multiply)),
                "MatShellSetOperation");
    petsc_check(MatShellSetOperation(m, MATOP_GET_DIAGONAL,
                                     reinterpret_cast<void (*)(void)>(&Petsc::get_diagonal)),
                "MatShellSetOperation");
    petsc_check(MatSetBlockSize(m, 3), "MatSetBlockSize");
    petsc_check(MatSetOption(m, MAT_SPD, PETSC_TRUE), "MatSetOption");
  };
  shell(p.fine, &Petsc::multiply<false>);
  shell(p.smoothed, &Petsc::multiply<true>);
  petsc_check(MatCreateVecs(p.fine, &p.x, &p.b), "MatCreateVecs");
  petsc_check(VecSet(p.x, 0.0), "VecSet");
}

void GeometricRankStatics::make_interpolation(const MeshPartition& coarse,
                                              const SoilOperator& coarse_op, int levels) {
  Petsc& p = *petsc_;
  RowSparse t;  // this rank's fine nodes x its coarse nodes (local numbers)
  on_every_rank(p.comm, [&] { t = nested_interpolation(coarse.mesh, part_.mesh, levels); });
  const RankRows columns = number_rows(coarse, p.comm);
  const auto count = static_cast<PetscInt>(columns.owned.size());
  const std::vector<char>& coarse_held = coarse_op.fixed();
  std::vector<PetscInt> diagonal(p.rows.owned.size(), 0), off(p.rows.owned.size(), 0);
  for (std::size_t k = 0; k < p.rows.owned.size(); ++k)
    for (int q = t.outerIndexPtr()[p.rows.owned[k]]; q < t.outerIndexPtr()[p.rows.owned[k] + 1];
         ++q) {
      const PetscInt column = columns.row[t.innerIndexPtr()[q]];
      ++(column >= columns.first && column < columns.first + count ? diagonal[k] : off[k]);
    }
  Mat& m = p.node_interpolation;
  petsc_check(MatCreate(p.comm, &m), "MatCreate");
  petsc_check(MatSetType(m, MATAIJ), "MatSetType");
  petsc_check(MatSetSizes(m, static_cast<PetscInt>(p.rows.owned.size()), count, PETSC_DETERMINE,
                          PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatXAIJSetPreallocation(m, 1, diagonal.data(), off.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
  for (std::size_t k = 0; k < p.rows.owned.size(); ++k) {
    const std::int32_t v = p.rows.owned[k];
    if (p.fixed[v]) continue;  // (a held DOF takes no correction)
    const PetscInt row = p.rows.first + static_cast<PetscInt>(k);
    for (int q = t.outerIndexPtr()[v]; q < t.outerIndexPtr()[v + 1]; ++q) {
      const int c = t.innerIndexPtr()[q];
      if (coarse_held[c]) continue;  // (nor gives one)
      const PetscInt column = columns.row[c];
      petsc_check(MatSetValue(m, row, column, t.valuePtr()[q], INSERT_VALUES), "MatSetValue");
    }
  }
  petsc_check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  petsc_check(MatCreateMAIJ(m, 3, &p.interpolation), "MatCreateMAIJ");
}

void GeometricRankStatics::build_solver(const MeshPartition& coarse,
                                        const SoilOperator& coarse_op) {
  Petsc& p = *petsc_;
  const RankRows rows = number_rows(coarse, p.comm);
  p.coarse = assemble_part_matrix(coarse, coarse_op, rows, p.comm);
  set_rigid_body_modes(p.coarse, coarse, rows, p.comm);
  p.ksp = static_cg(p.comm, p.fine, p.fine, tolerance_);
  set_two_level_multigrid(p.ksp, p.smoothed, p.coarse, p.interpolation);
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  PetscReal asked = tolerance_;  // (PETSC_OPTIONS' -fem_statics_ksp_rtol, if given, for the log)
  petsc_check(KSPGetTolerances(p.ksp, &asked, nullptr, nullptr, nullptr), "KSPGetTolerances");
  tolerance_ = asked;
  PetscErrorCode code = 0;
  {
    const SetUpOptions options;  // (GAMG's products on the coarse MPIAIJ matrix)
    code = KSPSetUp(p.ksp);
  }
  agree(p.comm, std::exchange(p.stop.failed, nullptr));  // (the smoothers' estimates' products)
  petsc_check(code, "KSPSetUp (the geometric multigrid's levels on the ranks)");
  levels_ = two_level_multigrid_levels(p.ksp);
}

Eigen::VectorXd GeometricRankStatics::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_on_ranks(p.ksp, p.x, p.b, p.stop, part_, p.rows, p.fixed, f, iterations_,
                        "the static solve on the ranks (PETSc's CG with the geometric multigrid)");
}

}  // namespace rumble::fem
