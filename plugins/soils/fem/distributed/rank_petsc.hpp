// What the solves on the ranks (issue #33; docs/fem-soil.md §8: the statics' distributed_statics
// .hpp with GAMG and geometric_rank_statics.hpp, the implicit step's rank_effective_system.hpp)
// share around PETSc: a matrix over the ranks' parts of a mesh, one solve, the options of GAMG's
// set-up. The matrix's rows are the ranks' owned nodes (each rank's in turn, in local order; a
// ghost takes its owner's number through the halo), 3 per node. K + S, or any combination
// k K + m M + S + d D (operator/effective_matrix.hpp), assembled from each rank's part of K as
// MPIAIJ (block size 3, preallocated from the part: a shared node's row gathers the pieces of
// every rank that holds it), the mass and the boundary's blocks on the owned nodes, fixed DOFs
// as identity rows and columns; the six rigid-body modes of the owned nodes as GAMG's near-null
// space. Included by those solvers' .cpp
// files only (no header of the room includes PETSc's but star_forest.hpp's MPI).
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>
#include <petscksp.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "operator/effective_matrix.hpp"
#include "operator/soil_operator.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct RankRows {
  std::vector<std::int32_t> owned;  // the local nodes this rank owns, in local order
  std::vector<PetscInt> row;        // per local node (owned and ghost): its node in the matrix
  PetscInt first = 0, total = 0;    // this rank's first node in the matrix; the matrix's nodes
};

/// What a solve on the ranks by an assembled matrix holds (the statics' GAMG, the implicit step's
/// factor): PETSc's session (outliving the rest), the matrix's rows, the matrix a, its vectors
/// (x: the last solution, b: the load) and the solver, destroyed by clear() or with it.
struct RankSolve {
  RankSolve() = default;
  RankSolve(const RankSolve&) = delete;
  RankSolve& operator=(const RankSolve&) = delete;
  ~RankSolve() { clear(); }
  void clear();  // (PETSc's errors ignored: a destructor's)
  std::shared_ptr<PetscSession> session = PetscSession::get();
  MPI_Comm comm = MPI_COMM_NULL;
  RankRows rows;
  Mat a = nullptr;
  Vec x = nullptr, b = nullptr;
  KSP ksp = nullptr;
  PetscStopTest stop;
};

/// The matrix's node of each of part's nodes, as above. Collective.
RankRows number_rows(const MeshPartition& part, MPI_Comm comm);

/// K + S of op (its part's rows of K, its boundary and fixed nodes, on part's nodes) as above,
/// marked symmetric positive definite. Collective; throws std::runtime_error when PETSc fails.
Mat assemble_part_matrix(const MeshPartition& part, const SoilOperator& op, const RankRows& rows,
                         MPI_Comm comm);
/// The same for the combination c of op's operators (c.stiffness K + c.mass M + S where
/// c.springs + c.dashpots D: operator/effective_matrix.hpp); K + S is {1, 0, true, 0}.
Mat assemble_part_combination(const MeshPartition& part, const SoilOperator& op,
                              const RankRows& rows, const Combination& c, MPI_Comm comm);

/// The rigid-body modes of the owned nodes (part.mesh's coordinates) as m's near-null space.
/// Collective; throws std::runtime_error when PETSc fails.
void set_rigid_body_modes(Mat m, const MeshPartition& part, const RankRows& rows, MPI_Comm comm);

/// PETSc's process-wide options for the span of GAMG's set-up on the ranks (MatPtAP and
/// MatMatMult read them without a prefix), each unless PETSC_OPTIONS gave it, restored after:
/// - "-matptap_via": a "rap" from PETSC_OPTIONS (one process's algorithm) is no algorithm of the
///   ranks' matrices (MPIAIJ's: scalable, nonscalable, allatonce, ...): it is taken out for the
///   span, so that GAMG's Galerkin products take the session's scalable
///   (statics/petsc_session.cpp);
/// - "-mat_product_clear" (kClearProducts, as one process's GAMG sets it).
class SetUpOptions {
 public:
  SetUpOptions();
  ~SetUpOptions();
  SetUpOptions(const SetUpOptions&) = delete;
  SetUpOptions& operator=(const SetUpOptions&) = delete;

 private:
  bool rap_ = false;
  ScopedPetscOption clear_{kClearProducts, "true"};
};

/// One solve on the ranks by ksp, set up on a matrix A of `rows` (x: its last solution, CG's
/// start, and b: vectors of the owned rows): u on every node of the part, owned and ghost, with
/// A u = f on the free DOFs (the statics' A: K + S), 0 on `fixed` ones (per local node); f: each
/// owned node's whole load [N] (the ghosts' are not read). `iterations`: ksp's (0 at rest, on
/// every rank alike). Every rank throws (agreed, rank_agreement.hpp) when ksp does not converge
/// ("fem: <method> did not converge ..."), when a rank's product failed (stop.failed: that rank's
/// message) or when rank 0's stop check threw (stop.stopped: rumble::Stopped), each seen in ksp's
/// test (statics/petsc_cg.hpp).
Eigen::VectorXd solve_on_ranks(KSP ksp, Vec x, Vec b, PetscStopTest& stop,
                               const MeshPartition& part, const RankRows& rows,
                               const std::vector<char>& fixed, const Eigen::VectorXd& f,
                               int& iterations, const char* method);

}  // namespace rumble::fem
