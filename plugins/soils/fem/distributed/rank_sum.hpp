// A sum over the ranks that every run repeats to the bit: each rank's value gathered to all and
// added in rank order (MPI_Allreduce may add in any order, so its last bits may change with the
// ranks' timing). For the few scalars a set-up needs (the Lanczos iterations' dot products, the
// far field's mean distance: docs/fem-soil.md §8), never for a vector.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <vector>

namespace rumble::fem {

/// The sum over the ranks of `mine`, added in rank order: the same on every rank, run after run.
inline double sum_in_rank_order(MPI_Comm comm, double mine) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<double> all(static_cast<std::size_t>(ranks));
  MPI_Allgather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm);
  double sum = 0.0;
  for (double s : all) sum += s;
  return sum;
}

}  // namespace rumble::fem
