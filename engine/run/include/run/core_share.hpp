// How the run's cores are shared between the participants while they step. The track steps on
// one thread (the engine integrates it); the soil may use several (rumble_host.threads). The
// statics, and a coupler that advances one participant at a time, leave the soil every core. A
// coupler that advances two at once (RUMBLE_CAP_THREADS: jacobi) starts with the cores split:
// one for the track, the others for the soil. After a first window of steps the host looks at
// what the participants did and gives the soil every core again when
//   - they never advanced at the same time (jacobi on one thread), or
//   - the track's advance took less than 1 / (2 cores) of the soil's: the soil is then nearly the
//     whole step (Amdahl: overlapping the track gains at most 1 / (1 - the track's share)), and
//     the core left to the track would idle most of it. The soil's extra thread shares a core
//     with the track while the track advances; a soil that tunes its team (the FEM soil's
//     ThreadTuner, docs/toolchain.md section 8) falls back to fewer threads where that is slower.
// Decided once: the two sides' costs per step do not change over a run (docs/couplers.md, "What
// the couplers cost").
#pragma once

#include <string>

namespace rumble {

class CoreShare {
 public:
  /// The decision is made on the steps after the first kSkipSteps (whose advance includes one-off
  /// work: the track's first factorization, the soil's first team trials) and kWindowSteps long.
  static constexpr int kSkipSteps = 5;
  static constexpr int kWindowSteps = 20;

  /// cores: the process's (usable_cpus()); two_at_once: the coupler may advance two
  /// participants at the same time.
  CoreShare(unsigned cores, bool two_at_once);

  /// The soil's threads for the first steps.
  unsigned first_grant() const { return grant_; }
  /// After a final step: the track's and the soil's advance time so far [s] (cumulative, as
  /// Participant::wall_seconds) and whether two participants advanced at once since the last
  /// call. Returns the soil's new thread count when it changes, else 0.
  unsigned after_step(double track_seconds, double soil_seconds, bool overlapped);
  /// Why the last change was made, for the log ("" before any).
  const std::string& reason() const { return reason_; }

 private:
  unsigned cores_;
  unsigned grant_;
  bool deciding_;
  int steps_ = 0;
  bool overlapped_ = false;
  double track_from_ = 0.0, soil_from_ = 0.0;  // s, the advance times when the window opened
  std::string reason_;
};

}  // namespace rumble
