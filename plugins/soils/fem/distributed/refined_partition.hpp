// mesh.refine on the ranks (issue #33: "the fine mesh never exists whole on one rank";
// docs/fem-soil.md §8 "mesh.refine on the ranks"): rank 0 splits gmsh's coarse mesh, and each
// rank refines its own part after the split, by one process's rule (uniform_refinement.hpp),
// level by level. The fine nodes are numbered from the coarse mesh's entities
// (numbered_refinement.hpp), so that a node on the seam between parts has one number on every
// rank; the ranks that hold it meet by that number (node_matching.hpp), which makes the halo.
// The fine tetrahedra are numbered as one process's refinement numbers them (tetrahedron e's
// children 8 e .. 8 e + 7 per level), and so are the ground faces (4 f .. 4 f + 3): the sums that
// follow their order (K's entries, the footprints' weights) are one process's.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include "distributed/mesh_partition.hpp"

namespace rumble::fem {

/// This rank's part of the whole coarse mesh refined `levels` times (1-3), as a partition of the
/// fine mesh: its nodes numbered as numbered_refinement.hpp numbers them (global), the shared
/// ones first, each group in the Morton order of its points (mesh/node_order.hpp: the product's
/// neighbours close in memory), the halo over them, tet_global and ground_global one process's.
/// coarse: partition_mesh(..., named = true)'s. from_root's roots on rank 0 are the fine mesh's
/// nodes in that global numbering. Collective. Throws std::invalid_argument when the fine mesh
/// has 2^31 nodes or more.
MeshPartition refine_partition(MPI_Comm comm, const MeshPartition& coarse, int levels);

}  // namespace rumble::fem
