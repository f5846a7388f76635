// Which machines a run's ranks share and what memory each has available (issue #33;
// docs/fem-soil.md, "Planning the ranks"): ranks on one machine share its memory, so a run's
// estimate per rank is held against each machine's memory for all of its ranks together,
// before meshing.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <vector>

#include "distributed/rank_plan.hpp"

namespace rumble::fem {

/// The memory this machine has available now [bytes]: MemAvailable or the cgroup's limit
/// (rumble/host_resources.hpp), or RUMBLE_FEM_NODE_MEMORY [bytes] when set, which exists for
/// tests/mpi alone (a machine's memory cannot be made small for a test).
double node_available_memory();

/// On rank 0, one share per machine of comm's ranks (MPI_COMM_TYPE_SHARED: the ranks that share
/// memory), with the memory its lowest rank sees available; empty on the other ranks.
/// Collective.
std::vector<NodeShare> node_shares(MPI_Comm comm);

}  // namespace rumble::fem
