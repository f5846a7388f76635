#include "distributed/geometric_rank_statics.hpp"

#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "distributed/rank_agreement.hpp"
#include "distributed/rank_fine_level.hpp"
#include "distributed/rank_petsc.hpp"
#include "statics/nested_interpolation.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct GeometricRankStatics::Petsc {
  Petsc(const MeshPartition& part, const SoilOperator& op, MPI_Comm comm) : level(part, op, comm) {}
  ~Petsc() {  // (errors ignored: a destructor)
    KSPDestroy(&ksp);
    MatDestroy(&interpolation);
    MatDestroy(&node_interpolation);
    MatDestroy(&coarse);
  }
  RankFineLevel level;
  Mat coarse = nullptr;
  Mat node_interpolation = nullptr;  // owned fine nodes x coarse nodes
  Mat interpolation = nullptr;       // the same on each of a node's 3 DOFs (MAIJ)
  KSP ksp = nullptr;
};

GeometricRankStatics::GeometricRankStatics(const MeshPartition& fine, const SoilOperator& op,
                                           const MeshPartition& coarse,
                                           const SoilOperator& coarse_op, int levels, MPI_Comm comm,
                                           double tolerance)
    : part_(fine), tolerance_(tolerance) {
  const auto start = std::chrono::steady_clock::now();
  petsc_ = std::make_unique<Petsc>(fine, op, comm);
  Petsc& p = *petsc_;
  make_interpolation(coarse, coarse_op, levels);
  build_solver(coarse, coarse_op);
  set_stop_test(p.ksp, op, p.level.stop);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

GeometricRankStatics::~GeometricRankStatics() = default;

void GeometricRankStatics::set_stop_check(std::function<void()> check) {
  petsc_->level.stop.check = std::move(check);
}

void GeometricRankStatics::make_interpolation(const MeshPartition& coarse,
                                              const SoilOperator& coarse_op, int levels) {
  Petsc& p = *petsc_;
  RowSparse t;  // this rank's fine nodes x its coarse nodes (local numbers)
  on_every_rank(p.level.comm, [&] { t = nested_interpolation(coarse.mesh, part_.mesh, levels); });
  const RankRows columns = number_rows(coarse, p.level.comm);
  const auto count = static_cast<PetscInt>(columns.owned.size());
  const std::vector<char>& coarse_held = coarse_op.fixed();
  std::vector<PetscInt> diagonal(p.level.rows.owned.size(), 0), off(p.level.rows.owned.size(), 0);
  for (std::size_t k = 0; k < p.level.rows.owned.size(); ++k)
    for (int q = t.outerIndexPtr()[p.level.rows.owned[k]];
         q < t.outerIndexPtr()[p.level.rows.owned[k] + 1]; ++q) {
      const PetscInt column = columns.row[t.innerIndexPtr()[q]];
      ++(column >= columns.first && column < columns.first + count ? diagonal[k] : off[k]);
    }
  Mat& m = p.node_interpolation;
  petsc_check(MatCreate(p.level.comm, &m), "MatCreate");
  petsc_check(MatSetType(m, MATAIJ), "MatSetType");
  petsc_check(MatSetSizes(m, static_cast<PetscInt>(p.level.rows.owned.size()), count,
                          PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatXAIJSetPreallocation(m, 1, diagonal.data(), off.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
  for (std::size_t k = 0; k < p.level.rows.owned.size(); ++k) {
    const std::int32_t v = p.level.rows.owned[k];
    if (p.level.fixed[v]) continue;  // (a held DOF takes no correction)
    const PetscInt row = p.level.rows.first + static_cast<PetscInt>(k);
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
  const RankRows rows = number_rows(coarse, p.level.comm);
  p.coarse = assemble_part_matrix(coarse, coarse_op, rows, p.level.comm);
  set_rigid_body_modes(p.coarse, coarse, rows, p.level.comm);
  p.ksp =
      p.level.two_level_cg(p.coarse, p.interpolation, tolerance_, levels_, "geometric multigrid");
}

Eigen::VectorXd GeometricRankStatics::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_on_ranks(p.ksp, p.level.x, p.level.b, p.level.stop, part_, p.level.rows,
                        p.level.fixed, f, iterations_,
                        "the static solve on the ranks (PETSc's CG with the geometric multigrid)");
}

}  // namespace rumble::fem
