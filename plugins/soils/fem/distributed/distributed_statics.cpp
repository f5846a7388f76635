#include "distributed/distributed_statics.hpp"

#include <petscksp.h>

#include <chrono>
#include <vector>

#include "distributed/rank_petsc.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct DistributedStatics::Petsc : RankSolve {  // (x: the last solution, CG's start)
  std::vector<char> fixed;                      // per local node: fixed (a zero load)
};

DistributedStatics::DistributedStatics(const MeshPartition& part, const SoilOperator& op,
                                       MPI_Comm comm)
    : part_(part), petsc_(std::make_unique<Petsc>()) {
  const auto start = std::chrono::steady_clock::now();
  Petsc& p = *petsc_;
  p.comm = comm;
  p.rows = number_rows(part, comm);
  p.fixed = op.fixed();
  p.a = assemble_part_matrix(part, op, p.rows, comm);
  // PETSc's matrix now holds the rows (completed over the ranks): the part's own are freed
  // before GAMG's hierarchy is built on top (built again if a later caller asks for them).
  op.release_stiffness();
  petsc_check(MatCreateVecs(p.a, &p.x, &p.b), "MatCreateVecs");
  petsc_check(VecSet(p.x, 0.0), "VecSet");
  build_solver();
  set_stop_test(p.ksp, op, p.stop);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

DistributedStatics::~DistributedStatics() = default;

void DistributedStatics::set_stop_check(std::function<void()> check) {
  petsc_->stop.check = std::move(check);
}

void DistributedStatics::build_solver() {
  Petsc& p = *petsc_;
  set_rigid_body_modes(p.a, part_, p.rows, p.comm);
  PC pc = nullptr;
  p.ksp = static_cg(p.comm, p.a, p.a, kTolerance);
  petsc_check(KSPGetPC(p.ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCGAMG), "PCSetType");
  // Plain aggregation, as one process's GAMG (statics/petsc_static_solver.cpp): on the stiff
  // example at 8.8e5 DOFs on 2 ranks 1.11-1.16 GB per rank at the statics against 1.68-1.69 GB
  // with one smoothing of the prolongator, a static start of 41 s against 37 s (93 CG
  // iterations to 1e-12 against 29): the ranks' memory is what limits their size
  // (docs/fem-soil.md §8).
  petsc_check(PCGAMGSetNSmooths(pc, 0), "PCGAMGSetNSmooths");
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  PetscErrorCode code = 0;
  {
    const SetUpOptions options;
    code = KSPSetUp(p.ksp);
  }
  petsc_check(code, "KSPSetUp (GAMG's hierarchy)");
  PetscInt levels = 0;
  petsc_check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  levels_ = static_cast<int>(levels);
}

Eigen::VectorXd DistributedStatics::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_on_ranks(p.ksp, p.x, p.b, p.stop, part_, p.rows, p.fixed, f, iterations_,
                        "the static solve on the ranks (PETSc's CG with GAMG)");
}

}  // namespace rumble::fem
