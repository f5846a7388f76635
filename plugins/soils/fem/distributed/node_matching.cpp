// The rendezvous of a node's holders (distributed/node_matching.hpp).
#include "distributed/node_matching.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <numeric>

namespace rumble::fem {
namespace {

/// Sends `width` int64 per entry to the ranks `to` (entries grouped by rank in the order given);
/// returns what this rank receives, grouped by the sending rank, and the counts it received.
std::vector<std::int64_t> exchange(MPI_Comm comm, const std::vector<std::int64_t>& send,
                                   const std::vector<int>& send_counts, int width,
                                   std::vector<int>* receive_counts) {
  const std::size_t ranks = send_counts.size();
  receive_counts->assign(ranks, 0);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts->data(), 1, MPI_INT, comm);
  std::vector<int> out_counts(ranks), in_counts(ranks), out_starts(ranks, 0), in_starts(ranks, 0);
  for (std::size_t r = 0; r < ranks; ++r) {
    out_counts[r] = width * send_counts[r];
    in_counts[r] = width * (*receive_counts)[r];
  }
  // (the starts as scans of their own: GCC 12.2 at -O3, the release build, computed the last
  // start as 0 when they were summed in the loop above under `if (r > 0)`, and MPI_Alltoallv
  // then wrote past `received`: every refined run on the ranks corrupted its heap, docs/
  // fem-soil.md §8; -O2 and Clang summed them right)
  std::exclusive_scan(out_counts.begin(), out_counts.end(), out_starts.begin(), 0);
  std::exclusive_scan(in_counts.begin(), in_counts.end(), in_starts.begin(), 0);
  std::vector<std::int64_t> received(static_cast<std::size_t>(in_starts.back() + in_counts.back()));
  MPI_Alltoallv(send.data(), out_counts.data(), out_starts.data(), MPI_INT64_T, received.data(),
                in_counts.data(), in_starts.data(), MPI_INT64_T, comm);
  return received;
}

/// The rendezvous's answers (holders, owner, owner's local number) to its entries (number,
/// local), received grouped by their sender (counts).
std::vector<std::int64_t> answer(const std::vector<std::int64_t>& entries,
                                 const std::vector<int>& counts) {
  const std::size_t n = entries.size() / 2;
  std::vector<int> sender(n);
  for (std::size_t r = 0, k = 0; r < counts.size(); ++r)
    for (int c = 0; c < counts[r]; ++c) sender[k++] = static_cast<int>(r);
  std::vector<std::size_t> order(n);  // by number, then sender
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return entries[2 * a] != entries[2 * b] ? entries[2 * a] < entries[2 * b]
                                            : sender[a] < sender[b];
  });
  std::vector<std::int64_t> out(3 * n);
  for (std::size_t first = 0, last = 0; first < n; first = last) {
    const std::int64_t number = entries[2 * order[first]];
    while (last < n && entries[2 * order[last]] == number) ++last;
    const auto holders = static_cast<std::int64_t>(last - first);
    const std::size_t owner = order[first + static_cast<std::size_t>(number % holders)];
    for (std::size_t k = first; k < last; ++k) {
      out[3 * order[k]] = holders;
      out[3 * order[k] + 1] = sender[owner];
      out[3 * order[k] + 2] = entries[2 * owner + 1];
    }
  }
  return out;
}

}  // namespace

std::vector<NodeMatch> match_nodes(MPI_Comm comm, const std::vector<std::int64_t>& number,
                                   const std::vector<std::int32_t>& local) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<int> send_counts(static_cast<std::size_t>(ranks), 0);
  for (std::int64_t g : number) ++send_counts[static_cast<std::size_t>(g % ranks)];
  std::vector<int> starts(send_counts.size(), 0);
  for (std::size_t r = 1; r < starts.size(); ++r) starts[r] = starts[r - 1] + send_counts[r - 1];
  std::vector<std::int64_t> send(2 * number.size());
  std::vector<std::size_t> slot(number.size());  // each entry's place in `send`
  std::vector<int> fill = starts;
  for (std::size_t k = 0; k < number.size(); ++k) {
    slot[k] = static_cast<std::size_t>(fill[static_cast<std::size_t>(number[k] % ranks)]++);
    send[2 * slot[k]] = number[k];
    send[2 * slot[k] + 1] = local[k];
  }
  std::vector<int> received_counts;
  const std::vector<std::int64_t> entries = exchange(comm, send, send_counts, 2, &received_counts);
  std::vector<int> unused;
  const std::vector<std::int64_t> answers =  // (back along the way the entries came)
      exchange(comm, answer(entries, received_counts), received_counts, 3, &unused);
  std::vector<NodeMatch> out(number.size());
  for (std::size_t k = 0; k < number.size(); ++k) {
    const std::int64_t* a = answers.data() + 3 * slot[k];
    out[k] = {static_cast<int>(a[0]), static_cast<int>(a[1]), static_cast<std::int32_t>(a[2])};
  }
  return out;
}

}  // namespace rumble::fem
