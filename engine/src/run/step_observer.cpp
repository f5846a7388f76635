#include "run/step_observer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "run/field_writer.hpp"
#include "run/participant.hpp"
#include "run/probe_recorder.hpp"
#include "run/run_recorder.hpp"
#include "run/summary_writer.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

// A footprint displacement beyond this [m] is not ground vibration: the coupled solution
// has blown up (typically an unstable explicit coupling with too large a macro step).
constexpr double kDivergedDisplacement = 1.0;

}  // namespace

StepObserver::StepObserver(const TrackParticipant& track, const SoilSide& soil, Sinks sinks,
                           double t_end, std::size_t every, std::filesystem::path results_dir,
                           bool progress)
    : track_(track),
      soil_(soil),
      sinks_(sinks),
      t_end_(t_end),
      every_(every),
      results_dir_(std::move(results_dir)),
      progress_(progress, t_end),
      scratch_(soil.output_size()) {}

void StepObserver::operator()(const StepOutcome& step) {
  // The recorder reads the track and the soil together: a step counts once final for both.
  // (Schemes that finish participants at different times, as two-step will, need a recorder
  // per participant; until then their partial reports are only counted.)
  if (!step.final_for(RUMBLE_PARTICIPANT_TRACK) || !step.final_for(RUMBLE_PARTICIPANT_SOIL)) {
    ++partial_;
    return;
  }
  t_reached_ = step.t + step.H;
  ++steps_;
  iterations_ += step.iterations;
  max_iterations_ = std::max(max_iterations_, step.iterations);
  if (!step.converged) ++unconverged_;
  for (const rumble_group_residual& g : step.residuals) {
    const std::string_view name = g.group != nullptr ? g.group : "";
    auto it = max_residuals_.find(name);  // heterogeneous: no string built once the key exists
    if (it == max_residuals_.end()) it = max_residuals_.emplace(std::string(name), 0.0).first;
    it->second = std::max(it->second, g.relative);
  }
  if (sinks_.probes != nullptr) sinks_.probes->take();
  if (sinks_.fields != nullptr) sinks_.fields->at(t_reached_);
  if (steps_ % every_ == 0 || t_reached_ >= t_end_ * (1.0 - 1e-12)) {
    sinks_.recorder.record(t_reached_, t_reached_ - t_recorded_, step.max_relative_residual(),
                           step.iterations);
    t_recorded_ = t_reached_;
  }
  check_finite(t_reached_);
  if (sinks_.summary != nullptr) sinks_.summary->heartbeat(t_reached_, steps_);
  if (interrupt_requested()) {
    std::ostringstream m;
    m << "interrupted at t = " << t_reached_ << " s (Ctrl-C); results up to that time are in "
      << results_dir_.string();
    throw Interrupted(m.str());
  }
  progress_.update(t_reached_);
}

void StepObserver::check_finite(double t) {
  const std::size_t n = track_.interface_size();
  soil_.get_output(scratch_.data());
  for (std::size_t i = 0; i < n; ++i) {
    const double u = scratch_[i];
    if (!std::isfinite(u) || std::abs(u) > kDivergedDisplacement) {
      std::ostringstream m;
      m << "simulation diverged at t = " << t << " s: footprint " << i << " displacement is " << u
        << " m (limit " << kDivergedDisplacement
        << " m). If the soil has no participating mass (winkler `m`, clm `m_f`), give it one: "
           "a massless soil and the ballast dashpots close a loop that explicit coupling does not "
           "survive at any time.macro_step (docs/decisions/0004); otherwise reduce "
           "time.macro_step";
      throw RunError(m.str());
    }
  }
  for (std::size_t w = 0; w < track_.vehicles().wheel_count(); ++w) {
    if (!std::isfinite(track_.contact_force(w))) {
      std::ostringstream m;
      m << "simulation diverged at t = " << t << " s: contact force of wheel " << w
        << " is not finite; reduce time.macro_step or track.integrator.micro_step";
      throw RunError(m.str());
    }
  }
}

}  // namespace rumble
