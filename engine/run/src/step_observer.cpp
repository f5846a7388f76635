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

StepObserver::StepObserver(const TrackParticipant& track, const SoilSide& soil,
                           std::vector<const SoilSide*> extras, Sinks sinks, double t_end,
                           std::size_t every, std::filesystem::path results_dir, bool progress,
                           scenario::DivergenceSpec divergence)
    : track_participant_(track),
      soil_side_(soil),
      extras_(std::move(extras)),
      sinks_(sinks),
      t_end_(t_end),
      every_(every),
      results_dir_(std::move(results_dir)),
      progress_(progress, t_end),
      extra_reach_(extras_.size()),
      divergence_(divergence),
      scratch_(soil.output_size()) {
  const std::size_t n = track.interface_size();
  soil.get_output(scratch_.data());
  divergence_.watch(soil.name(), scratch_.data(), n);
  for (const SoilSide* e : extras_) {
    e->get_output(scratch_.data());
    divergence_.watch(e->name(), scratch_.data(), n);
  }
}

bool StepObserver::Reach::advance(double t, std::size_t every, double t_end) {
  reached = t;
  ++steps;
  return steps % every == 0 || t >= t_end * (1.0 - 1e-12);
}

void StepObserver::operator()(const StepOutcome& step) {
  const double t = step.t + step.H;
  add_residuals(step);
  bool all = step.final_for(RUMBLE_PARTICIPANT_TRACK) && step.final_for(RUMBLE_PARTICIPANT_SOIL);
  if (step.final_for(RUMBLE_PARTICIPANT_TRACK)) on_track(t);
  if (step.final_for(RUMBLE_PARTICIPANT_SOIL)) on_soil(step, t);
  for (std::size_t e = 0; e < extras_.size(); ++e) {
    if (!step.final_for(static_cast<std::uint32_t>(e + 2))) {
      all = false;
      continue;
    }
    if (extra_reach_[e].advance(t, every_, t_end_)) sinks_.recorder.record_extra(e, t);
    check_soil(*extras_[e], e + 1, t, step.H);
  }
  if (!all) ++partial_;
  if (sinks_.summary != nullptr) sinks_.summary->heartbeat(t_reached(), soil_.steps);
  if (interrupt_requested()) {
    std::ostringstream m;
    m << "interrupted at t = " << t << " s (" << interrupt_cause()
      << "); results up to that time are in " << results_dir_.string();
    throw Interrupted(m.str());
  }
  // A scheme that finishes the participants one after the other is halfway at the track's end.
  progress_.update(0.5 * (track_.reached + soil_.reached));
}

void StepObserver::add_residuals(const StepOutcome& step) {
  bool predicted = false;
  for (const rumble_group_residual& g : step.residuals) {
    const char* group = StepOutcome::predicted_group(g);
    if (group == nullptr) {
      residuals_.add(g);
    } else {
      predictor_residuals_.add({group, g.absolute, g.relative});
      predicted = true;
    }
  }
  if (predicted) return;
  // No predictor reported: the final residuals are the predictor's (an explicit scheme).
  for (const rumble_group_residual& g : step.residuals) predictor_residuals_.add(g);
}

void StepObserver::on_track(double t) {
  if (track_.advance(t, every_, t_end_)) sinks_.recorder.record_track(t);
  for (std::size_t w = 0; w < track_participant_.vehicles().wheel_count(); ++w) {
    if (!std::isfinite(track_participant_.contact_force(w))) {
      std::ostringstream m;
      m << "simulation diverged at t = " << t << " s: contact force of wheel " << w
        << " is not finite; reduce time.macro_step or track.integrator.micro_step";
      throw RunError(m.str());
    }
  }
}

void StepObserver::on_soil(const StepOutcome& step, double t) {
  const bool record = soil_.advance(t, every_, t_end_);
  iterations_ += step.iterations;
  max_iterations_ = std::max(max_iterations_, step.iterations);
  shortest_step_ = std::min(shortest_step_, step.H);
  longest_step_ = std::max(longest_step_, step.H);
  if (!step.converged) ++unconverged_;
  if (sinks_.probes != nullptr) sinks_.probes->take();
  if (sinks_.fields != nullptr) sinks_.fields->at(t);
  if (record) {
    sinks_.recorder.record_soil(t, {step.max_relative_residual(), step.predictor_residual()},
                                step.iterations, step.H);
  }
  check_soil(soil_side_, 0, t, step.H);
}

void StepObserver::check_soil(const SoilSide& soil, std::size_t participant, double t, double H) {
  soil.get_output(scratch_.data());
  const std::size_t n = track_participant_.interface_size();  // outputs: u, then v
  divergence_.check(participant, scratch_.data(), scratch_.data() + n, n, t, H);
}

}  // namespace rumble
