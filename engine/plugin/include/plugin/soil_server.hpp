// Ranks other than 0 of an MPI launch (docs/decisions/0012-distributed-soil.md §1): each holds a
// copy of every distributed soil rank 0 creates, and makes on it every call rank 0 makes, with
// the same inputs, so that the soil's own collective operations meet. What those calls return is
// rank 0's; a server's outputs are dropped. An error is sent back to rank 0, which stops the run
// with it.
#pragma once

namespace rumble {

/// Serves rank 0 until it releases the servers (its parallel::finish()). Ignores Ctrl-C: the
/// launcher sends it to every rank and rank 0 alone decides how the run stops; a distributed soil
/// sees the stop only through rank 0 (it agrees on it with its peers, abi.h).
void serve_soils();

}  // namespace rumble
