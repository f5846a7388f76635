#include "distributed/rank_agreement.hpp"

#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
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

}  // namespace rumble::fem
