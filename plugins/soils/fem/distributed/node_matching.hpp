// Which ranks hold a node known by a global number alone (issue #33; docs/fem-soil.md §8
// "mesh.refine on the ranks"): the nodes of parts refined on the ranks are numbered from the
// coarse mesh (mesh/numbered_refinement.hpp), and a node on the seam between parts is made on
// every rank whose part holds it. Each rank sends its candidates to the rank number % ranks (a
// rendezvous: every node's holders meet on one rank, whatever the split), which counts them,
// chooses the owner and answers. No rank needs more than its own candidates and those it meets.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstdint>
#include <vector>

namespace rumble::fem {

struct NodeMatch {
  int holders = 0;               // ranks holding the node (1: this rank's alone)
  int owner = 0;                 // the rank that owns it
  std::int32_t owner_local = 0;  // its local number on the owner (the `local` it sent)
};

/// For each of this rank's nodes number[k] (local number local[k]): who holds it and owns it.
/// The owner is the holders' (in rank order) number % holders: every rank chooses alike, and the
/// seam's nodes spread over its ranks. Collective.
std::vector<NodeMatch> match_nodes(MPI_Comm comm, const std::vector<std::int64_t>& number,
                                   const std::vector<std::int32_t>& local);

}  // namespace rumble::fem
