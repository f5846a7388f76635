#include "distributed/rank_effective_system.hpp"

#include <petscksp.h>

#include <sstream>
#include <string>

#include "distributed/rank_petsc.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct RankEffectiveSystem::Petsc : RankSolve {};  // (stop: no test, a factor's solve)

namespace {

/// Why MUMPS's factor failed, from its error INFOG(1) (its codes: docs/fem-soil.md §8, "The
/// implicit scheme on the ranks").
std::string mumps_failure(PC pc) {
  Mat factor = nullptr;
  PetscInt error = 0;
  if (PCFactorGetMatrix(pc, &factor) != 0 || MatMumpsGetInfog(factor, 1, &error) != 0)
    return "out of memory, or not positive definite";
  const std::string code = " (its INFOG(1) " + std::to_string(error) + ")";
  if (error == -10) return "a zero pivot, the matrix is not positive definite" + code;
  if (error == -8 || error == -9 || error == -13 || error == -14 || error == -19)
    return "out of memory" + code;
  return "error" + code;
}

}  // namespace

RankEffectiveSystem::RankEffectiveSystem(const MeshPartition& part, const SoilOperator& op,
                                         MPI_Comm comm)
    : part_(part), op_(op), petsc_(std::make_unique<Petsc>()) {
  petsc_->comm = comm;
  petsc_->rows = number_rows(part, comm);
}

RankEffectiveSystem::~RankEffectiveSystem() = default;

void RankEffectiveSystem::build(const Combination& c, double dt) {
  Petsc& p = *petsc_;
  p.clear();  // (a former step size's factor first: two are never held at once)
  p.a = assemble_part_combination(part_, op_, p.rows, c, p.comm);
  op_.release_stiffness();  // (PETSc's matrix holds the rows now; the steps read their blocks)
  petsc_check(MatCreateVecs(p.a, &p.x, &p.b), "MatCreateVecs");
  petsc_check(KSPCreate(p.comm, &p.ksp), "KSPCreate");
  petsc_check(KSPSetOperators(p.ksp, p.a, p.a), "KSPSetOperators");
  petsc_check(KSPSetType(p.ksp, KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  petsc_check(KSPGetPC(p.ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  petsc_check(KSPSetOptionsPrefix(p.ksp, "fem_implicit_"), "KSPSetOptionsPrefix");
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  const PetscErrorCode code = KSPSetUp(p.ksp);
  PCFailedReason failed = PC_NOERROR;
  if (code == 0) PCGetFailedReason(pc, &failed);
  if (code == 0 && failed == PC_NOERROR) return;
  std::ostringstream m;  // (MUMPS's status is global: every rank takes this branch)
  m << "fem: the implicit step's matrix could not be factored on the ranks at dt = " << dt
    << " s (MUMPS through PETSc: " << mumps_failure(pc)
    << "); use the explicit scheme, or spread the factor over more ranks or machines";
  if (code != 0) petsc_check(code, m.str().c_str());
  throw std::runtime_error(m.str());
}

Eigen::VectorXd RankEffectiveSystem::solve(const Eigen::VectorXd& r) {
  Petsc& p = *petsc_;
  int iterations = 0;
  return solve_on_ranks(p.ksp, p.x, p.b, p.stop, part_, p.rows, op_.fixed(), r, iterations,
                        "the implicit step's solve on the ranks (MUMPS's Cholesky factor)");
}

}  // namespace rumble::fem
