#include "distributed/rank_agreement.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rumble::fem {

namespace {

std::string message_of(std::exception_ptr failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an exception not derived from std::exception";
  }
}

/// Whether every rank reaches this call within `grace` seconds: each failed, all at once (what
/// agree() throws, or a refusal every rank reaches after the same collective call).
bool every_rank_failed(MPI_Comm comm, double grace) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // (point-to-point messages of their own tag: they match no collective call the other ranks
  // may be waiting in)
  constexpr int kTag = 7275;
  const int mine = 1;
  std::vector<int> theirs(static_cast<std::size_t>(ranks), 0);
  std::vector<MPI_Request> requests;
  requests.reserve(2 * static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r) {
    if (r == rank) continue;
    requests.emplace_back();
    MPI_Issend(&mine, 1, MPI_INT, r, kTag, comm, &requests.back());
    requests.emplace_back();
    MPI_Irecv(&theirs[r], 1, MPI_INT, r, kTag, comm, &requests.back());
  }
  const double until = MPI_Wtime() + grace;
  int done = 0;
  while (true) {
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done) return true;
    if (MPI_Wtime() > until) return false;  // (the requests die with the process)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

void agree(MPI_Comm comm, std::exception_ptr failure, bool stop) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // (the worst status over the ranks, and the lowest rank that has it: MAXLOC's tie rule)
  struct {
    int status, rank;
  } mine{failure ? 2 : (stop && rank == 0 ? 1 : 0), rank}, worst{0, 0};
  MPI_Allreduce(&mine, &worst, 1, MPI_2INT, MPI_MAXLOC, comm);
  if (worst.status == 0) return;
  if (worst.status == 1) throw rumble::Stopped("stopped at the host's request (Ctrl-C)");
  std::string message = rank == worst.rank ? message_of(failure) : std::string();
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, worst.rank, comm);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, worst.rank, comm);
  if (rank == worst.rank) std::rethrow_exception(failure);
  const std::string soil = "fem: ";  // (its messages' start, said once)
  if (message.compare(0, soil.size(), soil) == 0) message.erase(0, soil.size());
  throw std::runtime_error(soil + "on rank " + std::to_string(worst.rank) + ": " + message);
}

void on_every_rank(MPI_Comm comm, const std::function<void()>& work) {
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  agree(comm, failure);
}

void on_root(MPI_Comm comm, const std::function<void()>& work) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::exception_ptr failure;
  if (rank == 0) {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
  }
  agree(comm, failure);
}

void collective(MPI_Comm comm, const std::function<void()>& work) {
  try {
    work();
  } catch (...) {
    const std::exception_ptr e = std::current_exception();
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    if (ranks == 1 || every_rank_failed(comm, kFailureGrace)) throw;
    stop_every_rank(comm, message_of(e));
  }
}

void stop_every_rank(MPI_Comm comm, const std::string& message) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string soil = "fem: ";
  const std::string what =
      message.compare(0, soil.size(), soil) == 0 ? message.substr(soil.size()) : message;
  std::fprintf(stderr,
               "fem: on rank %d: %s\nfem: rank %d failed alone, where the other ranks may wait in "
               "an exchange it never reaches: every rank is stopped (MPI_Abort, exit code 3), "
               "without a summary.json (docs/fem-soil.md §8, \"Failures\")\n",
               rank, what.c_str(), rank);
  std::fflush(stderr);
  MPI_Abort(comm, 3);
  std::abort();  // (MPI_Abort does not return)
}

}  // namespace rumble::fem
