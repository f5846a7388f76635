// The peak resident memory of each phase of a run (issue #33: memory per phase, in summary.json).
// Linux keeps the process's peak resident set (VmHWM in /proc/self/status) and lets the process
// start it anew at its current size (writing "5" to /proc/self/clear_refs, Linux >= 4.0): each
// phase's peak is then its own, not the largest before it. Where /proc does not allow that, the
// peaks are the process's since it started, and say so.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rumble {

/// The process's peak resident memory [bytes] since it started or the last restart; 0 where
/// /proc/self/status does not tell.
std::uint64_t peak_resident_bytes();

/// Starts a new peak at the current resident size; false where the system does not allow it.
bool restart_peak_resident();

/// Phases in order, each with its own peak: end(name) closes the phase begun at the previous
/// end() (or at construction, which takes the process's peak so far: the phase before a run's
/// first is its validation, the soil's meshing included).
class PhasePeaks {
 public:
  PhasePeaks() = default;
  void end(const std::string& phase);
  const std::vector<std::pair<std::string, std::uint64_t>>& peaks() const { return peaks_; }
  /// Whether every phase after the first has a peak of its own (the restart worked).
  bool separate() const { return separate_; }

 private:
  std::vector<std::pair<std::string, std::uint64_t>> peaks_;
  bool separate_ = true;
};

}  // namespace rumble
