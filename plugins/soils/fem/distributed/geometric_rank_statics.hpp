// The static state on the ranks by the geometric multigrid of mesh.refine's nested meshes
// (statics.solver geometric under mpirun; issue #33, docs/fem-soil.md §7.1 and §8): one
// process's solver (statics/geometric_static_solver.hpp) with each level split as the ranks
// split the meshes. With mesh.refine each rank refined its own part of gmsh's coarse mesh
// (refined_partition.hpp), so the coarse part a rank's fine nodes came from is on that rank:
// - the fine level: rank_fine_level.hpp's shells over the ranks' operator (CG's K in double
//   from the part's tetrahedra, the smoother's as the step reads it; the part's rows freed),
//   smoothed by Chebyshev(2) with Jacobi (statics/two_level_multigrid.hpp): the solution is K's
//   to CG's tolerance (docs/fem-soil.md §8, "K without its rows");
// - the coarse level: K + S assembled on the coarse parts as MPIAIJ (rank_petsc.hpp, as GAMG's
//   matrix on the ranks), solved by one V-cycle of GAMG over the ranks;
// - the interpolation: each owned fine node's row of the nested linear elements' dyadic weights
//   (statics/nested_interpolation.hpp) from the coarse tetrahedron on its own rank around it,
//   its columns the coarse nodes (owned or ghosts, in the coarse matrix's numbering), the three
//   components alike (MAIJ); rows of held fine nodes and columns of held coarse nodes left out.
// The fine matrix is never assembled and the part's rows are not held: the statics hold the
// coarse level (1/8 of the fine DOFs per level), the interpolation, the diagonal and CG's
// vectors beside the step's float blocks. CG stops at 1e-12 of the load,
// as GAMG on the ranks (distributed_statics.hpp): the same K in double, so whole runs agree with
// one process's to 1e-10. Every call is collective; PETSc's errors and CG's failure throw on
// every rank.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <memory>

#include "distributed/mesh_partition.hpp"
#include "distributed/rank_statics.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class GeometricRankStatics final : public RankStatics {
 public:
  /// fine: the soil's part, refined `levels` times from `coarse` on this rank
  /// (refine_partition); op: its operator (both kept alive by the caller); coarse_op: K + S on
  /// the coarse part (part_operator.hpp), read here only. Throws std::runtime_error on every
  /// rank when PETSc fails, std::invalid_argument when fine is no refinement of coarse.
  GeometricRankStatics(const MeshPartition& fine, const SoilOperator& op,
                       const MeshPartition& coarse, const SoilOperator& coarse_op, int levels,
                       MPI_Comm comm, double tolerance = kTolerance);
  ~GeometricRankStatics() override;
  GeometricRankStatics(const GeometricRankStatics&) = delete;
  GeometricRankStatics& operator=(const GeometricRankStatics&) = delete;

  Eigen::VectorXd solve(const Eigen::VectorXd& f) override;
  const char* method() const override { return "CG with the geometric multigrid"; }
  /// `tolerance`, or PETSC_OPTIONS' -fem_statics_ksp_rtol.
  void set_stop_check(std::function<void()> check) override;
  double tolerance() const override { return tolerance_; }
  static constexpr double kTolerance = 1e-12;

 private:
  struct Petsc;
  void make_interpolation(const MeshPartition& coarse, const SoilOperator& coarse_op, int levels);
  void build_solver(const MeshPartition& coarse, const SoilOperator& coarse_op);

  const MeshPartition& part_;
  std::unique_ptr<Petsc> petsc_;
  double tolerance_;
};

}  // namespace rumble::fem
