// What the local time stepping's choice (time/local_steps_choice.cpp) reads of K's whole rows on
// a rank, whose part holds a shared node's row only in part (part_stiffness.hpp): each entry
// between two shared nodes is K's on the lowest rank that holds it and zero on the others, every
// other entry on one rank alone. docs/fem-soil.md §8, "Local time stepping on the ranks".
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "operator/csr_matrix.hpp"

namespace rumble::fem {

/// Per DOF of the part's nodes: sum_j |K_kj| over K's whole row, the part's sums added over the
/// ranks at the shared nodes (each entry whole on one rank). Collective over the partition's
/// ranks.
std::vector<double> whole_magnitude_sums(const MeshPartition& part, const CsrMatrix& K);

/// Per node of the part: how many nodes j with flag[j] (per local node, alike at every copy) K's
/// whole row couples it to, i itself included, as one process counts them. An entry between two
/// shared nodes may sit in several ranks' patterns, so those are counted at the row's owner,
/// once per distinct pair of nodes; the others on the one rank that holds them. Collective.
std::vector<std::int32_t> whole_flagged_neighbours(const MeshPartition& part, const CsrMatrix& K,
                                                   const std::vector<char>& flag, MPI_Comm comm);

}  // namespace rumble::fem
