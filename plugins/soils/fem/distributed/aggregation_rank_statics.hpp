// The static state on the ranks without an assembled fine matrix (statics.solver aggregation,
// and auto under mpirun without mesh.refine; issue #33, docs/fem-soil.md §8, "The statics on the
// ranks without an assembled matrix"): CG preconditioned by a two-level aggregation multigrid.
// GAMG on the ranks (distributed_statics.hpp) holds PETSc's copy of K + S (12 B a nonzero, about
// 0.5 kB per DOF of a rank's share) and forms its first Galerkin product from it; this forms
// that level from the mesh instead:
// - the fine level: rank_fine_level.hpp's shells (CG's K in double from the part's tetrahedra,
//   the smoother's as the step reads it; the part's rows freed), smoothed by Chebyshev(2) with
//   Jacobi (statics/two_level_multigrid.hpp);
// - the interpolation: plain aggregation's tentative prolongator (statics/node_aggregates.hpp)
//   on each rank's owned free nodes (aggregates do not cross ranks: each rank's rows of P are
//   its own aggregates' columns), six coarse DOFs per aggregate, the rigid-body modes;
// - the coarse level: A_c = P^T (K + S) P summed tetrahedron by tetrahedron (P_e^T K_e P_e on
//   each rank's tetrahedra, a ghost node's rows of P from its owner) and at each boundary node,
//   assembled as MPIAIJ of block size 6, solved by one V-cycle of GAMG with the rigid-body
//   modes' coarse vectors as its near-null space.
// The statics then hold P (18 nonzeros per node), A_c, GAMG's hierarchy on it and CG's vectors
// beside the step. CG stops at 1e-12 of the load, as GAMG on the ranks: the same K in double,
// so whole runs agree with one process's to 1e-10. Every call is collective; PETSc's errors
// and CG's failure throw on every rank.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <memory>
#include <string>

#include "distributed/mesh_partition.hpp"
#include "distributed/rank_statics.hpp"
#include "operator/element_stiffness.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class AggregationRankStatics final : public RankStatics {
 public:
  /// part: the soil's part; op: its operator (both kept alive by the caller); elements: K_e of
  /// part's tetrahedra (read here only). Throws std::runtime_error on every rank when PETSc
  /// fails.
  AggregationRankStatics(const MeshPartition& part, const SoilOperator& op,
                         const ElementStiffness& elements, MPI_Comm comm,
                         double tolerance = kTolerance);
  ~AggregationRankStatics() override;
  AggregationRankStatics(const AggregationRankStatics&) = delete;
  AggregationRankStatics& operator=(const AggregationRankStatics&) = delete;

  Eigen::VectorXd solve(const Eigen::VectorXd& f) override;
  const char* method() const override { return "CG with the aggregation multigrid"; }
  void set_stop_check(std::function<void()> check) override;
  /// `tolerance`, or PETSC_OPTIONS' -fem_statics_ksp_rtol.
  double tolerance() const override { return tolerance_; }
  /// The first coarse level's DOFs over the ranks (6 per aggregate), against the fine level's.
  std::string levels_detail() const override;
  static constexpr double kTolerance = 1e-12;

 private:
  struct Petsc;

  const MeshPartition& part_;
  std::unique_ptr<Petsc> petsc_;
  double tolerance_;
  long long coarse_dofs_ = 0, fine_dofs_ = 0;  // over the ranks
};

}  // namespace rumble::fem
