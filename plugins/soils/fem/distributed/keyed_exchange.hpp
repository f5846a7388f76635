// Blocks of K between two nodes sent from every rank to every other in one MPI all-to-all, each
// named by its two nodes' numbers in rank 0's mesh: how a rank's pieces of K's shared entries
// reach the rank that sums them (part_stiffness.cpp) and how the local time stepping's counts
// over K's whole rows are made (whole_rows.cpp).
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <vector>

namespace rumble::fem {

/// What one rank sends or receives in an all-to-all: per rank a count of blocks, in rank order.
struct KeyedExchange {
  std::vector<int> counts, starts;  // per rank, in blocks
  std::vector<int> keys;            // 2 per block: its two nodes in rank 0's mesh
  std::vector<double> values;       // `width` per block

  /// starts from counts.
  void set_starts();
  /// The blocks received or sent in all.
  int blocks() const { return starts.empty() ? 0 : starts.back() + counts.back(); }
};

/// Sends `width` doubles per block (and with keys, the keys; then `in`'s counts and starts are
/// made first) from `out` to each rank; `in` gets what every rank sent here, in rank order.
/// Collective over comm.
void all_to_all(MPI_Comm comm, const KeyedExchange& out, KeyedExchange& in, int width, bool keys);

}  // namespace rumble::fem
