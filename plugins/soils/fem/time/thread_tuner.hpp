// The explicit step's team size, chosen from the step's own wall time. Each step ends at OpenMP
// barriers, which wait for the slowest thread: on a machine where other processes want the cores
// (a build, another run, a study's runs side by side), a thread of the team is descheduled for a
// scheduler's time slice and the whole team waits, and two threads were measured 6-30 times
// slower than one (docs/toolchain.md section 8, bench/threads/busy_machine.py). No setting known
// before the run can tell, so the soil tries: it times a trial of steps on each team size from
// the host's grant down to one (halving), steps on the fastest, and tries again after a hold that
// doubles while the choice stands (a busy machine changes). The team size changes no result: each
// node's sums run in the same order on any team (operator/symmetric_blocks.hpp).
#pragma once

#include <string>
#include <vector>

namespace rumble::fem {

class ThreadTuner {
 public:
  /// A trial: at least this much wall time [s] (several scheduler time slices of some ms, so
  /// that a descheduled thread shows in the trial's mean) and this many steps. The time decides
  /// on small meshes; on large ones (10-40 ms a step at 1e6 DOFs) a few steps already span it,
  /// and each step more of a losing size's trial is lost: 16 steps put 8-9 % of a 13 s stepping
  /// at 1.0e6 DOFs on one thread (docs/toolchain.md §8).
  static constexpr int kTrialSteps = 4;
  static constexpr double kTrialSeconds = 0.05;
  /// Steps after a change of team size that no trial counts (threads waking, caches) [-].
  static constexpr int kWarmUpSteps = 2;
  /// Wall time on a choice before the first new round of trials [s], doubled after each round
  /// that confirms it, up to kLongestHold.
  static constexpr double kFirstHold = 1.0;
  static constexpr double kLongestHold = 32.0;

  /// `granted`: the threads the host grants (at least 1 is used).
  explicit ThreadTuner(unsigned granted = 1) { grant(granted); }

  /// A new grant starts the trials again (the same grant changes nothing).
  void grant(unsigned granted);
  /// The team size for the next step.
  unsigned threads() const { return sizes_[current_]; }
  /// The step just taken on threads() threads took `seconds` of wall time.
  void record(double seconds);

  /// Seconds of stepping on each team size so far, largest size first (sizes()).
  const std::vector<double>& seconds_on() const { return seconds_on_; }
  const std::vector<unsigned>& sizes() const { return sizes_; }
  /// "2 threads 97 % of the stepping time, 1 thread 3 %" (empty before any step).
  std::string account() const;

 private:
  void end_trial();
  void choose();

  std::vector<unsigned> sizes_;     // the grant, then halvings down to 1
  std::vector<double> mean_;        // s per step in the last trial of each size
  std::vector<double> seconds_on_;  // s of stepping on each size
  std::size_t current_ = 0;         // index in sizes_
  bool trying_ = true;              // a round of trials, else holding the choice
  int warm_up_ = 0, steps_ = 0;     // of the current trial
  double trial_seconds_ = 0.0;      // s
  double held_ = 0.0, hold_ = 0.0;  // s: on the choice, and how long to hold it
  std::size_t chosen_ = 0;          // the choice before this round
};

}  // namespace rumble::fem
