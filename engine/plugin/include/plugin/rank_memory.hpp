// Every rank's peak resident memory per phase of a run under `mpirun -n N` (issue #33;
// docs/decisions/0015-memory-per-rank.md): when rank 0 ends a phase (core/peak_memory.hpp) it asks
// the other ranks, which serve it (cli/rank_server.hpp), for theirs; each answers with its peak
// since its previous phase's end and starts a new one, as rank 0 does. The engine measures, not
// the soil: every rank is the engine's process whatever soil it serves, and the ABI is unchanged.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace rumble {

/// The other ranks' peaks at the end of one phase.
struct ServerPeaks {
  std::vector<std::uint64_t> bytes;  // ranks 1..N-1 in rank order [bytes]; 0: not measured
  bool separate = true;              // every one of them restarted its peak
};

/// Rank 0 of a launch of N > 1 ranks, at a phase's end: the other ranks' peaks since their
/// previous phase's end, each restarted; nothing on one process. Collective with
/// answer_phase_end on every other rank.
std::optional<ServerPeaks> end_phase_on_servers();

/// A rank other than 0, given a Service::kPhaseEnd message: sends rank 0 its peak and restarts
/// it.
void answer_phase_end();

}  // namespace rumble
