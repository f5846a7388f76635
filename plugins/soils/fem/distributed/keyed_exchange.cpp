#include "distributed/keyed_exchange.hpp"

namespace rumble::fem {

void KeyedExchange::set_starts() {
  starts.assign(counts.size(), 0);
  for (std::size_t r = 1; r < counts.size(); ++r) starts[r] = starts[r - 1] + counts[r - 1];
}

void all_to_all(MPI_Comm comm, const KeyedExchange& out, KeyedExchange& in, int width, bool keys) {
  const auto ranks = out.counts.size();
  if (keys) {
    in.counts.assign(ranks, 0);
    MPI_Alltoall(out.counts.data(), 1, MPI_INT, in.counts.data(), 1, MPI_INT, comm);
    in.set_starts();
  }
  const auto scaled = [](const std::vector<int>& v, int by) {
    std::vector<int> s(v);
    for (int& x : s) x *= by;
    return s;
  };
  const int blocks = in.blocks();
  if (keys) {
    in.keys.assign(static_cast<std::size_t>(2 * blocks), 0);
    MPI_Alltoallv(out.keys.data(), scaled(out.counts, 2).data(), scaled(out.starts, 2).data(),
                  MPI_INT, in.keys.data(), scaled(in.counts, 2).data(), scaled(in.starts, 2).data(),
                  MPI_INT, comm);
  }
  in.values.assign(static_cast<std::size_t>(width) * blocks, 0.0);
  if (width == 0) return;
  MPI_Alltoallv(out.values.data(), scaled(out.counts, width).data(),
                scaled(out.starts, width).data(), MPI_DOUBLE, in.values.data(),
                scaled(in.counts, width).data(), scaled(in.starts, width).data(), MPI_DOUBLE, comm);
}

}  // namespace rumble::fem
