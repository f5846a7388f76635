// How the ranks of the distributed soil fail (plugins/soils/fem/distributed/rank_agreement.hpp;
// issue #33's "a rank that fails stops all ranks with the message, not a hang"):
//   together: inside collective(),
//     - a failure agreed on (on_every_rank, rank 1 failing) is rethrown on every rank at once:
//       rank 1's own message there, "fem: on rank 1: ..." on the others;
//     - a failure every rank makes alike, each its own exception after the same collective
//       call (as a refusal every rank reaches), is rethrown on every rank, well within
//       kFailureGrace;
//     - work that does not fail returns on every rank.
//   alone: rank 1 fails inside collective() while the others wait in a barrier there: rank 1 says
//     its message and why every rank stops on stderr, then MPI_Abort ends them all (exit code 3;
//     its test matches the message and mpirun's banner, and a hang is its timeout).
// usage: mpirun -n N rank_failure_check together|alone   (together: exit code 0 when all held)
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "distributed/rank_agreement.hpp"

namespace {

using rumble::fem::collective;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// What collective(work) threw on this rank ("" if nothing).
std::string thrown_by(MPI_Comm comm, void (*work)(MPI_Comm)) {
  try {
    collective(comm, [&] { work(comm); });
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

int failed = 0;
void expect(bool ok, const char* what, const std::string& got) {
  if (ok) return;
  ++failed;
  std::printf("rank_failure_check: FAILED on rank %d: %s (got \"%s\")\n", rank_of(MPI_COMM_WORLD),
              what, got.c_str());
}

int together(MPI_Comm comm) {
  const int rank = rank_of(comm);
  std::string got = thrown_by(comm, [](MPI_Comm c) {
    rumble::fem::on_every_rank(c, [c] {
      if (rank_of(c) == 1) throw std::runtime_error("fem: rank 1's part failed");
    });
  });
  expect(got == (rank == 1 ? "fem: rank 1's part failed" : "fem: on rank 1: rank 1's part failed"),
         "an agreed failure is rethrown on every rank with rank 1's message", got);

  const double start = MPI_Wtime();
  got = thrown_by(comm, [](MPI_Comm c) {
    MPI_Barrier(c);
    throw std::invalid_argument("fem: refused alike on rank " + std::to_string(rank_of(c)));
  });
  expect(got == "fem: refused alike on rank " + std::to_string(rank),
         "a failure every rank makes is rethrown on each, its own", got);
  const double waited = MPI_Wtime() - start;
  expect(waited < 0.5 * rumble::fem::kFailureGrace,
         "ranks failing alike learn it well within the grace", std::to_string(waited) + " s");

  got = thrown_by(comm, [](MPI_Comm c) { MPI_Barrier(c); });
  expect(got.empty(), "work that does not fail returns on every rank", got);
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, comm);
  return any;
}

void alone(MPI_Comm comm) {
  collective(comm, [comm] {
    if (rank_of(comm) == 1) throw std::runtime_error("fem: failed alone on purpose");
    MPI_Barrier(comm);  // (never left: rank 1 stops every rank)
  });
  std::printf("rank_failure_check: FAILED rank %d left the barrier\n", rank_of(comm));
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  const char* mode = argc > 1 ? argv[1] : "";
  int code = 2;
  if (std::strcmp(mode, "together") == 0) {
    code = together(MPI_COMM_WORLD) == 0 ? 0 : 1;
  } else if (std::strcmp(mode, "alone") == 0) {
    alone(MPI_COMM_WORLD);
    code = 1;
  } else if (rank_of(MPI_COMM_WORLD) == 0) {
    std::printf("usage: mpirun -n N rank_failure_check together|alone\n");
  }
  MPI_Finalize();
  return code;
}
