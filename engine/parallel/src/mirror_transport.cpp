#include "parallel/mirror_transport.hpp"

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <thread>

namespace rumble::parallel {
namespace {

constexpr std::int64_t kReleased = -1;  // a header's length: no message, the servers may go

/// Waits for `request` to complete: spins on MPI_Test for the first 0.2 ms (calls of a run follow
/// each other closely), then sleeps between tests, 10 us growing to 1 ms.
void wait_politely(MPI_Request& request) {
  int done = 0;
  const auto start = std::chrono::steady_clock::now();
  auto nap = std::chrono::microseconds(10);
  for (MPI_Test(&request, &done, MPI_STATUS_IGNORE); done == 0;
       MPI_Test(&request, &done, MPI_STATUS_IGNORE)) {
    if (std::chrono::steady_clock::now() - start < std::chrono::microseconds(200)) continue;
    std::this_thread::sleep_for(nap);
    nap = std::min(nap * 2, std::chrono::microseconds(1000));
  }
}

void broadcast_header(std::int64_t& length) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(&length, 1, MPI_INT64_T, 0, MPI_COMM_WORLD, &request);
  wait_politely(request);
}

}  // namespace

void send_to_servers(const std::vector<char>& message) {
  std::int64_t length = static_cast<std::int64_t>(message.size());
  broadcast_header(length);
  MPI_Bcast(const_cast<char*>(message.data()), static_cast<int>(length), MPI_CHAR, 0,
            MPI_COMM_WORLD);
}

/// Rank 0's finish(): the header that ends every server's loop.
void release_servers() {
  std::int64_t length = kReleased;
  broadcast_header(length);
}

std::optional<std::vector<char>> next_from_root() {
  std::int64_t length = 0;
  broadcast_header(length);
  if (length == kReleased) return std::nullopt;
  std::vector<char> message(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
  return message;
}

std::vector<std::vector<char>> gather_to_root(const std::vector<char>& mine) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(rank == 0 ? static_cast<std::size_t>(size) : 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(lengths.size(), 0);
  int total = 0;
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    offsets[k] = total;
    total += lengths[k];
  }
  std::vector<char> all(static_cast<std::size_t>(total));
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  std::vector<std::vector<char>> each;
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    const auto from = all.begin() + offsets[k];
    each.emplace_back(from, from + lengths[k]);
  }
  return each;
}

std::string first_failure(const std::string& mine) {
  const std::vector<std::vector<char>> each =
      gather_to_root(std::vector<char>(mine.begin(), mine.end()));
  for (std::size_t k = 0; k < each.size(); ++k) {
    if (!each[k].empty())
      return "rank " + std::to_string(k) + ": " + std::string(each[k].begin(), each[k].end());
  }
  return "";
}

}  // namespace rumble::parallel
