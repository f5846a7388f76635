#include "distributed/node_memory.hpp"

#include <cstdlib>
#include <rumble/host_resources.hpp>
#include <string>

namespace rumble::fem {

double node_available_memory() {
  if (const char* fake = std::getenv("RUMBLE_FEM_NODE_MEMORY"); fake != nullptr && *fake != '\0')
    return std::strtod(fake, nullptr);
  return available_memory_bytes();
}

std::vector<NodeShare> node_shares(MPI_Comm comm) {
  int rank = 0, ranks = 1, here = 0, local_ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  MPI_Comm machine = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &machine);
  MPI_Comm_rank(machine, &here);
  MPI_Comm_size(machine, &local_ranks);
  MPI_Comm_free(&machine);
  // Per rank: whether it speaks for its machine (its lowest rank), its ranks, its memory.
  const double mine[3] = {here == 0 ? 1.0 : 0.0, static_cast<double>(local_ranks),
                          here == 0 ? node_available_memory() : 0.0};
  std::vector<double> all(rank == 0 ? 3 * static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(mine, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, 0, comm);
  std::vector<NodeShare> shares;
  for (int r = 0; r < (rank == 0 ? ranks : 0); ++r)
    if (all[3 * r] != 0.0)
      shares.push_back({static_cast<int>(all[3 * r + 1]), r == 0, all[3 * r + 2]});
  return shares;
}

}  // namespace rumble::fem
