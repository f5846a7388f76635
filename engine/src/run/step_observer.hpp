// What the engine does after every final macro step a coupler reports: record it (CSV rows,
// receiver samples, field snapshots), check that the coupled solution has not blown up, beat
// summary.json's heartbeat, honour Ctrl-C between steps, and move the progress line. It throws to
// stop the run (the host keeps the exception and the coupler returns).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "run/cosim_host.hpp"
#include "run/progress_line.hpp"

namespace rumble {

class FieldWriter;
class ProbeRecorder;
class RunRecorder;
class SoilSide;
class SummaryWriter;
class TrackParticipant;

class StepObserver {
 public:
  /// Where a final step goes; probes and fields may be null (not asked for, or not offered),
  /// summary too (no heartbeat).
  struct Sinks {
    RunRecorder& recorder;
    ProbeRecorder* probes = nullptr;
    FieldWriter* fields = nullptr;
    SummaryWriter* summary = nullptr;
  };
  StepObserver(const TrackParticipant& track, const SoilSide& soil, Sinks sinks, double t_end,
               std::size_t every, std::filesystem::path results_dir, bool progress);

  /// The host's step callback. Throws RunError when the run diverged, Interrupted on Ctrl-C.
  void operator()(const StepOutcome& step);

  /// The largest relative residual of each channel group the coupler reported, over the run.
  const std::map<std::string, double, std::less<>>& max_residuals() const { return max_residuals_; }
  double t_reached() const { return t_reached_; }  // s, end of the last recorded step
  std::size_t steps() const { return steps_; }     // final steps, for track and soil
  std::size_t partial_reports() const { return partial_; }
  /// Coupler iterations over the final steps (1 per step for explicit schemes), the most in one
  /// step, and the steps the coupler reported as not converged.
  std::uint64_t iterations() const { return iterations_; }
  std::uint32_t max_iterations() const { return max_iterations_; }
  std::size_t unconverged_steps() const { return unconverged_; }

 private:
  void check_finite(double t);

  const TrackParticipant& track_;
  const SoilSide& soil_;
  Sinks sinks_;
  double t_end_;       // s
  std::size_t every_;  // record every n-th step
  std::filesystem::path results_dir_;
  ProgressLine progress_;
  double t_reached_ = 0.0, t_recorded_ = 0.0;  // s
  std::size_t steps_ = 0, partial_ = 0, unconverged_ = 0;
  std::uint64_t iterations_ = 0;
  std::uint32_t max_iterations_ = 0;
  std::vector<double> scratch_;                               // soil outputs, sized once
  std::map<std::string, double, std::less<>> max_residuals_;  // by group; keys made once
};

}  // namespace rumble
