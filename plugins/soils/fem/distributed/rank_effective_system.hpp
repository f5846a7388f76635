// The implicit step's effective system on the ranks (issue #33; docs/fem-soil.md §8, "The
// implicit scheme on the ranks"): K_eff = k K + m M + S + d D (time/implicit_solver.hpp)
// assembled over the ranks' parts as the statics' matrix is (rank_petsc.hpp) and factored by
// MUMPS's Cholesky through PETSc, once per step size, the factor spread over the ranks as one
// process's CHOLMOD factor is held whole. PETSC_OPTIONS with the prefix "fem_implicit_" tunes
// the solve (another factor package, or -fem_implicit_ksp_type cg with a preconditioner). Every
// call is collective.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <Eigen/Core>
#include <memory>

#include "distributed/mesh_partition.hpp"
#include "operator/soil_operator.hpp"
#include "time/implicit_solver.hpp"

namespace rumble::fem {

class RankEffectiveSystem final : public EffectiveSystem {
 public:
  /// op: this rank's operator on part's nodes (kept alive by the caller).
  RankEffectiveSystem(const MeshPartition& part, const SoilOperator& op, MPI_Comm comm);
  ~RankEffectiveSystem() override;
  RankEffectiveSystem(const RankEffectiveSystem&) = delete;
  RankEffectiveSystem& operator=(const RankEffectiveSystem&) = delete;

  /// Assembles K_eff from the part's rows of K (built again where the statics freed them, and
  /// freed after: the step reads its own upper blocks) and factors it. Throws std::runtime_error
  /// on every rank when PETSc or MUMPS fails (out of memory, not positive definite).
  void build(const Combination& c, double dt) override;
  /// w' on every node of the part, owned and ghost (the ghosts take their owners' values).
  Eigen::VectorXd solve(const Eigen::VectorXd& r) override;

 private:
  struct Petsc;
  const MeshPartition& part_;
  const SoilOperator& op_;
  std::unique_ptr<Petsc> petsc_;
};

}  // namespace rumble::fem
