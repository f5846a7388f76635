// How the ranks of a distributed soil agree that a piece of work went well, so that one rank's
// failure stops every rank with its message and none waits for ever in a collective call the
// failed rank never reaches (docs/decisions/0012-distributed-soil.md §1: "not a hang").
//
// The host gathers each call's errors and reports the lowest failing rank's. So after a failure
// every rank throws: the lowest failing rank its own exception, the others the same message
// naming that rank ("fem: on rank 1: ..."), which rank 0 then reports when it is not the one
// that failed. rumble::Stopped (Ctrl-C, asked on rank 0) stops every rank alike.
//
// Where no agreement can be made (a rank fails inside a collective call, or between two of
// them, while the others already wait in the next one), `collective` is the last resort: it
// says the failing rank's message on stderr and stops every rank with MPI_Abort (exit code 3),
// never a hang. It tells the two apart by whether every rank fails within a few seconds.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <exception>
#include <functional>
#include <string>

namespace rumble::fem {

/// Every rank: whether its own work failed (null: it did not) and, on rank 0, whether the host
/// asks to stop. Returns when every rank did well and no stop is asked; else throws on every
/// rank as above. Collective (one MPI_Allreduce; a failure adds a broadcast of its message).
void agree(MPI_Comm comm, std::exception_ptr failure, bool stop = false);

/// Runs work on every rank (work makes no collective call: its exception could not reach the
/// others), then agree().
void on_every_rank(MPI_Comm comm, const std::function<void()>& work);

/// Runs work on rank 0 alone (the other ranks wait), then agree().
void on_root(MPI_Comm comm, const std::function<void()>& work);

/// Seconds a failed rank waits in collective() for the others to fail too [s]: ranks that fail
/// alike do so after the same collective call, within milliseconds of each other.
constexpr double kFailureGrace = 10.0;

/// Runs work, which makes collective calls over comm, on every rank: the distributed soil's
/// lay-out and statics (fem_distributed.cpp). An exception that every rank throws within
/// kFailureGrace is rethrown on each, its own (what agree() throws, a refusal every rank
/// reaches). One that this rank throws alone stopped it perhaps while the others wait in a
/// collective call it never reaches: it is said on stderr and every rank is stopped
/// (stop_every_rank). On one rank every exception is rethrown.
void collective(MPI_Comm comm, const std::function<void()>& work);

/// Says "fem: on rank R: <message>" on stderr with why every rank stops, then stops them all
/// (MPI_Abort, exit code 3): for a failure inside a collective call, where no agreement can reach
/// the other ranks (an OpenMP region's exchange, collective() above).
[[noreturn]] void stop_every_rank(MPI_Comm comm, const std::string& message);

}  // namespace rumble::fem
