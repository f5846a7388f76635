// The fine level of the ranks' matrix-free statics (issue #33; docs/fem-soil.md §8): the
// geometric multigrid of mesh.refine's nested meshes (geometric_rank_statics.hpp) and the
// aggregation multigrid without mesh.refine (aggregation_rank_statics.hpp) share it. PETSc shell
// matrices whose rows are the ranks' owned nodes, over the ranks' operator's products
// (distributed_operator.hpp: each rank's part, the shared nodes' sums exchanged by the halo),
// held DOFs as identity rows and columns:
// - `fine`, CG's operator: K in double, formed from the part's tetrahedra (the part's rows are
//   freed: operator/element_stiffness.hpp);
// - `smoothed`, the smoother's and the multigrid residual's: K as the step reads it (its float
//   blocks, within 6e-8 of each entry), so the preconditioner is a fixed linear operator close
//   to K^-1 while CG's residual is K's in double (docs/fem-soil.md §8, "K without its rows");
// both with the diagonal of K + S for Jacobi. Included by those solvers' .cpp files only.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>
#include <petscksp.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "distributed/rank_petsc.hpp"
#include "operator/soil_operator.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"
#include "statics/two_level_multigrid.hpp"

namespace rumble::fem {

struct RankFineLevel {
  /// Frees op's rows (release_stiffness) and makes the shells and CG's vectors x (zero) and b.
  /// part and op must outlive this, which must stay at its address (the shells' context).
  /// Collective; throws std::runtime_error when PETSc fails.
  RankFineLevel(const MeshPartition& part, const SoilOperator& op, MPI_Comm comm);
  ~RankFineLevel();  // (PETSc's errors ignored: a destructor's)
  RankFineLevel(const RankFineLevel&) = delete;
  RankFineLevel& operator=(const RankFineLevel&) = delete;

  /// y = (K + S) x over the ranks, K in double (kStepped false) or as the step reads it (true):
  /// MATOP_MULT, collective as MatMult is. x's held entries are taken out first, so the shell is
  /// symmetric for any x, as the smoother's estimate of the spectrum needs. A failed product (it
  /// still made its exchanges) is kept in `stop.failed` and gives y = x: a PETSc error here would
  /// end MatMult on this rank alone while the others wait in CG's next sum; CG ends at the next
  /// iteration on every rank instead, and the ranks agree on the failure.
  template <bool kStepped>
  static PetscErrorCode multiply(Mat a, Vec x, Vec y);
  /// The diagonal of K + S on the owned DOFs (1 on held ones): MATOP_GET_DIAGONAL, for Jacobi.
  static PetscErrorCode get_diagonal(Mat a, Vec d);

  /// CG on `fine` to `tolerance` of the load (or PETSC_OPTIONS' -fem_statics_ksp_rtol, written
  /// back) preconditioned by the two-level multigrid on `smoothed`, `coarse` and `interpolation`
  /// (statics/two_level_multigrid.hpp), set up (GAMG's products under SetUpOptions), the
  /// smoothers' failed products agreed over the ranks. Returns it and sets `levels`. `what`
  /// names the multigrid in PETSc's error. Collective; throws on every rank.
  KSP two_level_cg(Mat coarse, Mat interpolation, double& tolerance, int& levels, const char* what);

  std::shared_ptr<PetscSession> session = PetscSession::get();
  MPI_Comm comm = MPI_COMM_NULL;
  const MeshPartition* part = nullptr;
  const SoilOperator* op = nullptr;
  RankRows rows;
  std::vector<char> fixed;   // per local node: held
  Eigen::VectorXd diagonal;  // per owned DOF
  Eigen::VectorXd in, out;   // per local DOF, the shells'
  Mat fine = nullptr, smoothed = nullptr;
  Vec x = nullptr, b = nullptr;  // x: the last solution (CG's start)
  PetscStopTest stop;
};

}  // namespace rumble::fem
