#include "distributed/part_stiffness.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "distributed/keyed_exchange.hpp"

namespace rumble::fem {

namespace {

// An entry block of K between two shared nodes: node `row`'s `position`-th neighbour.
struct BlockAt {
  std::int32_t row = 0;
  std::int64_t position = 0;
};

// This rank's pieces of the blocks between two shared nodes, each sent to its row node's owner
// (the block's home, where its pieces are summed), with where each sits here.
KeyedExchange shared_pieces(const MeshPartition& part, const CsrMatrix& K, int ranks,
                            std::vector<BlockAt>& at) {
  std::vector<std::vector<BlockAt>> to(static_cast<std::size_t>(ranks));
  for (std::int32_t i = 0; i < part.shared; ++i)
    for (std::int64_t p = 0; p < K.degree(i); ++p)
      if (K.neighbours(i)[p] < part.shared) to[part.owner[i]].push_back({i, p});
  KeyedExchange out;
  for (const std::vector<BlockAt>& blocks : to) {
    out.counts.push_back(static_cast<int>(blocks.size()));
    for (const BlockAt& b : blocks) {
      at.push_back(b);
      out.keys.push_back(part.global[b.row]);
      out.keys.push_back(part.global[K.neighbours(b.row)[b.position]]);
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) out.values.push_back(K.block_entry(b.row, b.position, c, d));
    }
  }
  out.set_starts();
  return out;
}

// At the home: each block's pieces summed in rank order, and its keeper (the lowest rank that
// sent a piece); the reply to each piece is its block's sum (9) and keeper (1).
KeyedExchange sum_pieces(const KeyedExchange& in) {
  std::unordered_map<std::int64_t, std::size_t> slot;
  std::vector<double> sums;
  std::vector<int> keeper;
  std::vector<std::size_t> slot_of;
  for (std::size_t r = 0; r < in.counts.size(); ++r)
    for (int k = in.starts[r]; k < in.starts[r] + in.counts[r]; ++k) {
      const std::int64_t key = (static_cast<std::int64_t>(in.keys[2 * k]) << 32) |
                               static_cast<std::uint32_t>(in.keys[2 * k + 1]);
      const auto [it, made] = slot.try_emplace(key, keeper.size());
      if (made) {
        keeper.push_back(static_cast<int>(r));
        sums.insert(sums.end(), 9, 0.0);
      }
      for (int v = 0; v < 9; ++v) sums[9 * it->second + v] += in.values[9 * k + v];
      slot_of.push_back(it->second);
    }
  KeyedExchange reply{in.counts, in.starts, {}, {}};
  for (const std::size_t s : slot_of) {
    reply.values.insert(reply.values.end(), sums.begin() + 9 * s, sums.begin() + 9 * s + 9);
    reply.values.push_back(keeper[s]);
  }
  return reply;
}

// K_ji = K_ij^T for each pair with i before j in one process's node order.
void symmetrize(const MeshPartition& part, CsrMatrix& K) {
  for (std::int32_t j = 0; j < part.nodes(); ++j)
    for (std::int64_t q = 0; q < K.degree(j); ++q) {
      const std::int32_t i = K.neighbours(j)[q];
      if (!part.precedes(i, j)) continue;
      const std::int32_t* row = K.neighbours(i);
      const std::int64_t p = std::lower_bound(row, row + K.degree(i), j) - row;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) K.block_row(j, i, c)[d] = K.block_entry(i, p, d, c);
    }
}

}  // namespace

void complete_shared_entries(const MeshPartition& part, CsrMatrix& K, MPI_Comm comm) {
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  std::vector<BlockAt> at;
  const KeyedExchange out = shared_pieces(part, K, ranks, at);
  KeyedExchange in;
  all_to_all(comm, out, in, 9, true);
  const KeyedExchange reply = sum_pieces(in);
  KeyedExchange back{out.counts, out.starts, {}, {}};
  all_to_all(comm, reply, back, 10, false);
  for (std::size_t k = 0; k < at.size(); ++k) {
    const double* whole = back.values.data() + 10 * k;
    const bool kept = static_cast<int>(whole[9]) == rank;
    const std::int32_t j = K.neighbours(at[k].row)[at[k].position];
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) K.block_row(at[k].row, j, c)[d] = kept ? whole[3 * c + d] : 0.0;
  }
  symmetrize(part, K);
}

void complete_mass(const MeshPartition& part, Eigen::VectorXd& mass) {
  part.halo->sum_to_roots(mass.data(), mass.data(), 1);
  part.halo->to_leaves(mass.data(), mass.data(), 1);
}

}  // namespace rumble::fem
