// The soil's mesh split over the ranks by PETSc's DMPlex (docs/decisions/0012-distributed-soil.md
// §4; docs/fem-soil.md, "On many ranks"): rank 0's whole mesh becomes a DMPlex (its tetrahedra
// and nodes only, not interpolated), PT-Scotch partitions its tetrahedra (DMPlexDistribute, no
// overlap), and each rank receives its tetrahedra and every node they touch. A node on tetrahedra
// of several ranks is shared: one of them owns it (DMPlex's point star forest), the others hold
// a ghost copy. The explicit step updates owned and ghost nodes alike from the same complete
// product, so that every copy of a node holds the same value (distributed_operator.hpp).
//
// The local numbering puts the shared nodes first (the halo, whose products are summed over the
// ranks while the interior's are computed) and each group in the order of rank 0's mesh (its
// node order keeps neighbours close, mesh/node_order.hpp); the tetrahedra keep rank 0's order,
// so that each entry of K on a rank's interior sums its elements in the order of one process.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "distributed/star_forest.hpp"
#include "mesh/numbered_refinement.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

struct MeshPartition {
  /// This rank's tetrahedra and nodes, and those of its tetrahedra's faces that lie on the
  /// ground or the truncation surface (each such face is a face of one tetrahedron, so of one
  /// rank: the surfaces are split with the tetrahedra), ordered by their tetrahedron.
  TetMesh mesh;
  std::vector<std::int32_t> global;         // per local node: its node in rank 0's mesh
  std::vector<std::int32_t> tet_global;     // per local tetrahedron: its index in rank 0's mesh
  std::vector<std::int32_t> ground_global;  // per face of mesh.ground: its index in rank 0's
  std::vector<int> owner;                   // per local node: the rank that owns it
  std::int32_t shared = 0;                  // local nodes [0, shared) are shared with other ranks
  std::int64_t global_nodes = 0;            // rank 0's mesh
  std::int64_t global_tetrahedra = 0;
  /// The halo over the shared nodes [0, shared): each ghost is a leaf of its owner's node.
  std::unique_ptr<StarForest> halo;
  /// From rank 0's nodes (the roots, on rank 0 alone) to every rank's local nodes (leaves).
  std::unique_ptr<StarForest> from_root;

  std::int32_t nodes() const { return static_cast<std::int32_t>(global.size()); }
  bool owns(std::int32_t local, int rank) const { return owner[local] == rank; }
  /// The local node of rank 0's node g, or -1 when this rank does not hold it.
  std::int32_t local_of(std::int32_t g) const;

  std::vector<std::int32_t> by_global;  // the local nodes sorted by their global number
  /// Refined on the ranks (refined_partition.hpp): per local node, its Morton key in the whole
  /// mesh's box; one process orders the nodes by (key, global). Empty: by global alone.
  std::vector<std::uint64_t> morton;
  /// Whether local node i comes before j in one process's node order.
  bool precedes(std::int32_t i, std::int32_t j) const {
    if (!morton.empty() && morton[i] != morton[j]) return morton[i] < morton[j];
    return global[i] < global[j];
  }
  /// When the partition was asked to name them (partition_mesh's `named`): the whole mesh's
  /// numbers of this part's nodes, tetrahedra, edges and faces, for refine_partition.
  CoarseNames names;
};

/// The mesh's dual graph: two tetrahedra adjacent where they share a face, in compressed rows
/// (tetrahedron e's neighbours are adjacent[start[e]] to adjacent[start[e + 1] - 1]).
struct FaceGraph {
  std::vector<std::int32_t> start;
  std::vector<std::int32_t> adjacent;
};

/// The graph PT-Scotch splits (partition_mesh, partition_on_one_process): the one PETSc's
/// DMPlexCreatePartitionerGraph makes of a DMPlex without faces, each row in its order (the
/// tetrahedra around t[0] in ascending order, then those around t[1] not listed yet, ...), since
/// PT-Scotch's split depends on the order of the edges. Made from each node's tetrahedra: 0.8 s
/// at 1.0e6 DOFs, where PETSc's took 29.6 s (docs/fem-soil.md §8, "The split's time").
FaceGraph face_graph(const TetMesh& mesh);

/// The partition's name in the log: which partitioner DMPlex used.
const char* partitioner_name();

/// Splits `whole` (rank 0's mesh; nullptr on the other ranks) over comm's ranks; named: each
/// tetrahedron's edges and faces numbered on rank 0 (name_entities) travel with it, into
/// MeshPartition::names. Collective. Throws std::runtime_error on every rank when a rank gets no
/// tetrahedra (naming the counts and the fix), and when PETSc fails.
MeshPartition partition_mesh(MPI_Comm comm, const TetMesh* whole, bool named = false);

/// Each tetrahedron's part in a split of `whole` into `parts` parts on this one process: the
/// split partition_mesh hands to DMPlexDistribute (PT-Scotch on face_graph from the same seed,
/// on rank 0 alone), for `rumble mesh --ranks N` (split_plan.hpp). Needs a PETSc session
/// (statics/petsc_session.hpp). Throws std::runtime_error when PETSc fails.
std::vector<int> partition_on_one_process(const TetMesh& whole, int parts);

}  // namespace rumble::fem
