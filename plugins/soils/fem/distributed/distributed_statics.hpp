// The static state on many ranks (issue #33; docs/fem-soil.md §8, §7.1): (K + S) u = f solved by
// PETSc's conjugate gradients with its algebraic multigrid GAMG over the ranks, each rank's part
// of K (part_stiffness.hpp) assembled into one matrix whose rows are the ranks' owned nodes
// (MATAIJ, block size 3, preallocated from each rank's part: a shared node's row gathers the
// pieces of every rank that holds it), S on the owned boundary nodes, fixed DOFs as identity rows
// and columns with a zero load. GAMG's near-null space is the six rigid-body modes from the owned
// nodes' coordinates, as on one process (statics/petsc_static_solver.hpp); PETSC_OPTIONS with
// the prefix "fem_statics_" tunes both.
//
// CG stops at 1e-12 of the load (one process's factor is exact; the ranks' states then agree
// to some 1e-10, the bound for whole runs) and starts from the last solution. Every call
// is collective.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <Eigen/Core>
#include <memory>

#include "distributed/mesh_partition.hpp"
#include "distributed/rank_statics.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class DistributedStatics final : public RankStatics {
 public:
  /// K + S of each rank's part (op: its operator on part's nodes), and GAMG's hierarchy.
  /// Throws std::runtime_error on every rank when PETSc fails.
  DistributedStatics(const MeshPartition& part, const SoilOperator& op, MPI_Comm comm);
  ~DistributedStatics();
  DistributedStatics(const DistributedStatics&) = delete;
  DistributedStatics& operator=(const DistributedStatics&) = delete;

  Eigen::VectorXd solve(const Eigen::VectorXd& f) override;
  const char* method() const override { return "CG with GAMG"; }
  void set_stop_check(std::function<void()> check) override;
  double tolerance() const override { return kTolerance; }
  static constexpr double kTolerance = 1e-12;

 private:
  struct Petsc;
  void build_solver();

  const MeshPartition& part_;
  std::unique_ptr<Petsc> petsc_;
};

}  // namespace rumble::fem
