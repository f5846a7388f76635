#include "distributed/whole_rows.hpp"

#include <algorithm>

#include "distributed/keyed_exchange.hpp"

namespace rumble::fem {

std::vector<std::int32_t> whole_flagged_neighbours(const MeshPartition& part,
                                                   const SoilOperator& blocks,
                                                   const std::vector<char>& flag, MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<double> count(static_cast<std::size_t>(part.nodes()), 0.0);   // (the halo's sums)
  std::vector<std::vector<int>> pairs_to(static_cast<std::size_t>(ranks));  // 2 keys per pair
  const auto entry = [&](std::int32_t i, std::int32_t j) {                  // K_ij, its row i
    if (!flag[j]) return;
    if (i >= part.shared || j >= part.shared) {
      count[i] += 1.0;  // (on this rank alone)
      return;
    }
    std::vector<int>& to = pairs_to[part.owner[i]];
    to.push_back(part.global[i]);
    to.push_back(part.global[j]);
  };
  blocks.for_each_step_block([&](std::int32_t i, std::int32_t j, const double*) {
    entry(i, j);
    if (j != i) entry(j, i);
  });
  KeyedExchange out, in;
  for (const std::vector<int>& to : pairs_to) {
    out.counts.push_back(static_cast<int>(to.size() / 2));
    out.keys.insert(out.keys.end(), to.begin(), to.end());
  }
  out.set_starts();
  all_to_all(comm, out, in, 0, true);
  // At the owner: each distinct pair once.
  std::vector<std::int64_t> pairs(static_cast<std::size_t>(in.blocks()));
  for (std::size_t k = 0; k < pairs.size(); ++k)
    pairs[k] = (static_cast<std::int64_t>(in.keys[2 * k]) << 32) |
               static_cast<std::uint32_t>(in.keys[2 * k + 1]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const std::int64_t pair : pairs)
    count[part.local_of(static_cast<std::int32_t>(pair >> 32))] += 1.0;
  part.halo->sum_to_roots(count.data(), count.data(), 1);
  part.halo->to_leaves(count.data(), count.data(), 1);
  std::vector<std::int32_t> whole(count.size());
  for (std::size_t i = 0; i < count.size(); ++i) whole[i] = static_cast<std::int32_t>(count[i]);
  return whole;
}

}  // namespace rumble::fem
