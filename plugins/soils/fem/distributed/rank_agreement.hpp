// How the ranks of a distributed soil agree that a piece of work went well, so that one rank's
// failure stops every rank with its message and none waits for ever in a collective call the
// failed rank never reaches (docs/decisions/0012-distributed-soil.md §1: "not a hang").
//
// The host gathers each call's errors and reports the lowest failing rank's. So after a failure
// every rank throws: the lowest failing rank its own exception, the others the same message
// naming that rank ("fem: on rank 1: ..."), which rank 0 then reports when it is not the one
// that failed. rumble::Stopped (Ctrl-C, asked on rank 0) stops every rank alike.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <exception>
#include <functional>

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

}  // namespace rumble::fem
