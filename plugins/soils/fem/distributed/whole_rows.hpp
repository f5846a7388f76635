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
#include "operator/soil_operator.hpp"

namespace rumble::fem {

/// Per node of the part: how many nodes j with flag[j] (per local node, alike at every copy) K's
/// whole row couples it to, i itself included, as one process counts them, from the part's
/// blocks (blocks.for_each_step_block). An entry between two shared nodes sits in the pattern of
/// every rank that holds a tetrahedron of both, so those are counted at the row's owner, once
/// per distinct pair of nodes; the others on the one rank that holds them. Collective.
std::vector<std::int32_t> whole_flagged_neighbours(const MeshPartition& part,
                                                   const SoilOperator& blocks,
                                                   const std::vector<char>& flag, MPI_Comm comm);

}  // namespace rumble::fem
