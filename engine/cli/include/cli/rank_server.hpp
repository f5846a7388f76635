// Ranks other than 0 of an MPI launch (docs/decisions/0012-distributed-soil.md): rank 0 runs the
// command, and this loop serves it until it releases the other ranks: a distributed soil's calls
// (plugin/soil_server.hpp), a study's runs (study/rank_share.hpp) and the ends of a run's phases
// (plugin/rank_memory.hpp: each rank's peak memory).
#pragma once

namespace rumble::cli {

/// Serves rank 0's messages until it releases this rank. Ignores SIGINT and SIGTERM, which
/// mpirun sends every rank: rank 0 alone decides how a run stops (a study's share listens while
/// its runs go).
void serve_rank_zero();

}  // namespace rumble::cli
