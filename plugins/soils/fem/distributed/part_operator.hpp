// The soil's operator on one rank's part of a mesh (distributed_operator.hpp), built from the
// part alone (issue #33; docs/fem-soil.md §8): K and the lumped mass of its tetrahedra completed
// over the ranks (part_stiffness.hpp), its boundary blocks (part_pieces.hpp) and, with a fixed
// boundary, its fixed nodes. For the soil's mesh (distributed_soil.hpp) and, with statics.solver
// geometric, for the coarse mesh it was refined from (geometric_rank_statics.hpp).
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <memory>
#include <rumble/plugin.hpp>
#include <vector>

#include "distributed/distributed_operator.hpp"
#include "distributed/mesh_partition.hpp"
#include "fem_settings.hpp"

namespace rumble::fem {

/// The operator on part (kept alive by the caller) with the settings' elasticity and boundary
/// (its springs fitted to the footprints), K read by the step in `precision`. Collective; a
/// degenerate tetrahedron's error thrown on every rank (rank_agreement.hpp).
std::unique_ptr<DistributedOperator> part_operator(const MeshPartition& part,
                                                   const FemSettings& settings,
                                                   const std::vector<Footprint>& footprints,
                                                   unsigned threads, StepPrecision precision,
                                                   MPI_Comm comm);

}  // namespace rumble::fem
