// What each rank builds from its own part of the mesh (issue #33; docs/fem-soil.md §8 "On many
// ranks"; docs/decisions/0012-distributed-soil.md): the truncation surface's blocks, the
// footprints' weights, the receivers' places and the far field's mean distance, each the same
// as one process's on the whole mesh (tests/mpi/fem_partition_check.cpp: to 1e-14, the sums
// over a shared node's faces being taken in another order). No rank needs the whole mesh: a
// part refined after the split (its tetrahedra, nodes and surface faces each split in eight and
// four) is built alike.
//
// Every function is collective over the partition's ranks.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstddef>
#include <rumble/plugin.hpp>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "fem_settings.hpp"
#include "operator/boundary_blocks.hpp"
#include "operator/footprint_loads.hpp"
#include "output/probe_locator.hpp"

namespace rumble::fem {

/// This rank's boundary nodes (local numbers) with their blocks: each node's share of the
/// truncation surface summed over the ranks whose faces touch it (the halo), then fitted as
/// absorbing_boundary fits them.
std::vector<BoundaryNode> part_boundary(const MeshPartition& part, const FemSettings& settings,
                                        const std::vector<Footprint>& footprints);

/// The footprints' weights on this rank's nodes (local numbers, owned and ghost): every rank's
/// ground faces under a footprint gathered on every rank (the footprints' faces, a few hundred
/// to a few thousand: small) and weighed as footprint_weights weighs them, in the whole mesh's
/// order of its ground faces: the one process's weights to the bit. Throws its error on every
/// rank alike.
FootprintWeights part_footprint_weights(MPI_Comm comm, const MeshPartition& part,
                                        const std::vector<Footprint>& footprints);

/// A receiver this rank samples: its index among the receivers and its place (local nodes).
struct PartProbe {
  std::size_t index = 0;
  ProbePoint point;
};
/// The receivers this rank samples: each receiver's best tetrahedron over the ranks' parts
/// (locate_probe's rule: the largest smallest barycentric coordinate, the first in rank 0's
/// order among equals), sampled by the rank that holds it. Throws locate_probe's error on every
/// rank when a receiver lies outside the mesh.
std::vector<PartProbe> part_probes(MPI_Comm comm, const MeshPartition& part,
                                   const std::vector<Probe>& probes);

/// The boundary nodes' mean distance [m] from the footprints' centre over the whole mesh
/// (StaticFarField::mean_distance), each node counted by its owner.
double boundary_mean_distance(MPI_Comm comm, const MeshPartition& part,
                              const std::vector<BoundaryNode>& boundary,
                              const std::vector<Footprint>& footprints);

}  // namespace rumble::fem
