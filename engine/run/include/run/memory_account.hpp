// The run's account of memory (issue #33): each phase's peak resident memory
// (core/peak_memory.hpp), per degree of freedom of the scenario's soil, and the soil's own
// estimate of the run's peak, asked for after its layout and logged before the statics spend it
// (ABI 1.5 size; docs/decisions/0014-abi-1-5.md). Under `mpirun -n N` every rank's peak per phase
// too, measured on each rank at the same phase ends (plugin/rank_memory.hpp;
// docs/decisions/0015-memory-per-rank.md). Written to summary.json's "memory" and, at the run's
// end, to the log.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/peak_memory.hpp"
#include "plugin/instance.hpp"

namespace rumble {

/// A run's phases' peaks on every rank: rank 0's own and, under mpirun -n N > 1, the other
/// ranks' at the same phase ends; on one process rank 0's alone.
class RunMemory {
 public:
  /// Ends the phase on rank 0 and then on the other ranks (collective under mpirun).
  void end(const std::string& phase);
  const PhasePeaks& own() const { return own_; }
  /// Per phase, in own().peaks()' order: ranks 1..N-1's peaks [bytes]; empty on one process.
  const std::vector<std::vector<std::uint64_t>>& others() const { return others_; }
  /// Whether every rank's every phase after the first has a peak of its own.
  bool separate() const { return own_.separate() && others_separate_; }

 private:
  PhasePeaks own_;
  std::vector<std::vector<std::uint64_t>> others_;
  bool others_separate_ = true;
};

/// The soil's size (nothing when it does not say); its estimate logged when it gives one.
std::optional<SoilInstance::Size> announce_soil_size(const SoilInstance& soil);

/// summary.json's "memory": rank 0's phases' peaks, and with the soil's size the bytes per DOF
/// and the estimate against the largest peak; under mpirun, "ranks": every rank's.
nlohmann::json memory_summary(const RunMemory& memory,
                              const std::optional<SoilInstance::Size>& soil);

/// One line: the run's peak, each phase's bytes per DOF, the estimate against it; under mpirun
/// a second: each rank's peak.
void log_memory(const RunMemory& memory, const std::optional<SoilInstance::Size>& soil);

}  // namespace rumble
