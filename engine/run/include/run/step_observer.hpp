// What the engine does after every final macro step a coupler reports: record it (CSV rows,
// receiver samples, field snapshots), check that the coupled solution has not blown up, beat
// summary.json's heartbeat, honour Ctrl-C between steps, and move the progress line. It throws to
// stop the run (the host keeps the exception and the coupler returns).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "run/cosim_host.hpp"
#include "run/divergence_monitor.hpp"
#include "run/progress_line.hpp"
#include "run/run_residuals.hpp"

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
  /// extras: the coupler's extra soils (participants 2, 3, ...), in order.
  /// After the statics: each soil's outputs are its static state (the divergence reference).
  StepObserver(const TrackParticipant& track, const SoilSide& soil,
               std::vector<const SoilSide*> extras, Sinks sinks, double t_end, std::size_t every,
               std::filesystem::path results_dir, bool progress,
               scenario::DivergenceSpec divergence);

  /// The host's step callback. Throws RunError when the run diverged, Interrupted on Ctrl-C.
  void operator()(const StepOutcome& step);

  /// Each participant's steps are recorded when the coupler reports them final: most schemes
  /// finish the track and the soil together, two_step the track (on its reduced soil) first.
  /// The interface residual of each channel group the coupler reported, over the run.
  const RunResiduals& residuals() const { return residuals_; }
  /// The residual of each step's predictor per channel group, over the run: the coupling error,
  /// of the scheme's order (StepOutcome::predictor_residual).
  const RunResiduals& predictor_residuals() const { return predictor_residuals_; }
  /// s: the time up to which both the track and the soil are final
  double t_reached() const { return std::min(track_.reached, soil_.reached); }
  std::size_t steps() const { return soil_.steps; }  // final steps of the soil
  /// Reports final for some participants only (two_step's are all partial).
  std::size_t partial_reports() const { return partial_; }
  /// Coupler iterations over the soil's final steps (1 per step for explicit schemes), the most in
  /// one step, and the steps the coupler reported as not converged.
  std::uint64_t iterations() const { return iterations_; }
  std::uint32_t max_iterations() const { return max_iterations_; }
  std::size_t unconverged_steps() const { return unconverged_; }
  /// s: the shortest and longest of the soil's final macro steps (0 before the first).
  double shortest_step() const { return soil_.steps > 0 ? shortest_step_ : 0.0; }
  double longest_step() const { return longest_step_; }
  const DivergenceMonitor& divergence() const { return divergence_; }

 private:
  /// Where one participant's final steps have got to.
  struct Reach {
    double reached = 0.0;   // s, end of its last final step
    std::size_t steps = 0;  // final steps so far
    /// Counts a final step ending at t; true when it is to be recorded (every n-th, the last).
    bool advance(double t, std::size_t every, double t_end);
  };
  void on_track(double t);
  void on_soil(const StepOutcome& step, double t);
  /// participant: the soil's index in divergence_ (0: the soil, 1 + e: extra e); the final step
  /// of length H [s] ends at t [s].
  void check_soil(const SoilSide& soil, std::size_t participant, double t, double H);

  const TrackParticipant& track_participant_;
  const SoilSide& soil_side_;
  std::vector<const SoilSide*> extras_;
  Sinks sinks_;
  double t_end_;       // s
  std::size_t every_;  // record every n-th step
  std::filesystem::path results_dir_;
  ProgressLine progress_;
  Reach track_, soil_;
  std::vector<Reach> extra_reach_;
  std::size_t partial_ = 0, unconverged_ = 0;
  std::uint64_t iterations_ = 0;
  std::uint32_t max_iterations_ = 0;
  double shortest_step_ = std::numeric_limits<double>::infinity(), longest_step_ = 0.0;  // s
  DivergenceMonitor divergence_;
  std::vector<double> scratch_;  // soil outputs, sized once
  RunResiduals residuals_, predictor_residuals_;
  /// Adds a step's residuals to residuals_ and predictor_residuals_.
  void add_residuals(const StepOutcome& step);
};

}  // namespace rumble
