#include "run/run_scenario.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <vector>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"
#include "run/cosim_host.hpp"
#include "run/crash_record.hpp"
#include "run/field_writer.hpp"
#include "run/participant.hpp"
#include "run/probe_recorder.hpp"
#include "run/run_components.hpp"
#include "run/run_recorder.hpp"
#include "run/step_observer.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A plugin calling exit() in the middle of a run ended rumble with exit code 0, a truncated run
// and summary.json still "running" (issue #8). While a run goes, exit() and quick_exit() are
// intercepted: summary.json says "aborted" and why, stderr too, and the process ends with exit
// code 3 whatever code was passed. (_exit() and signals cannot be caught so; a crash leaves
// "running" with a stale heartbeat, docs/scenario.md.)
std::atomic<bool> g_run_active{false};
std::atomic<SummaryWriter*> g_run_summary{nullptr};

void exit_during_run() {
  if (!g_run_active.exchange(false)) return;
  const std::string message =
      "the process was told to exit during the run (a plugin called exit()?); the run did not "
      "finish; the results up to the last completed macro step are on disk";
  if (SummaryWriter* summary = g_run_summary.exchange(nullptr))
    summary->fail(message, RunStatus::kAborted);
  std::fprintf(stderr, "rumble: error: %s\n", message.c_str());
  std::fflush(nullptr);
  std::_Exit(exit_code(RunStatus::kAborted));
}

/// Arms the interception for one run (handlers registered once per process).
class ExitGuard {
 public:
  ExitGuard() {
    static const bool registered = [] {
      std::atexit(exit_during_run);
      std::at_quick_exit(exit_during_run);
      return true;
    }();
    (void)registered;
    g_run_active = true;
  }
  ~ExitGuard() {
    g_run_active = false;
    g_run_summary = nullptr;
  }
  ExitGuard(const ExitGuard&) = delete;
  ExitGuard& operator=(const ExitGuard&) = delete;
  void watch(SummaryWriter& summary) { g_run_summary = &summary; }
};

struct Ending {
  RunStatus status = RunStatus::kCompleted;
  std::string message;
};

/// How the coupled run ended, from the coupler's status, what the host kept, and how far the
/// steps got.
Ending judge(const CosimHostImpl& host, rumble_status status, const std::string& coupler_message,
             const CouplerInstance& coupler, const StepObserver& observer, double t_end,
             const fs::path& results_dir) {
  // A plugin that honoured a stop request inside its step returns ERROR: an interruption too,
  // not a failure (the observer's own Interrupted, raised between steps, passes as it is).
  const auto interrupted_inside_step = [&] {
    std::ostringstream m;
    m << "interrupted (" << interrupt_cause()
      << ") inside the step after t = " << observer.t_reached()
      << " s; results up to that time are in " << results_dir.string();
    return Interrupted(m.str());
  };
  try {
    try {
      host.rethrow_if_failed();
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception&) {
      if (interrupt_requested()) throw interrupted_inside_step();
      throw;
    }
    if (status != RUMBLE_OK && interrupt_requested()) throw interrupted_inside_step();
    if (status == RUMBLE_ERROR || status == RUMBLE_FATAL)
      throw RunError("coupler '" + coupler.type_name() + "' failed: " + coupler_message);
    if (observer.t_reached() < t_end - 1e-9 * t_end) {
      throw RunError("coupler '" + coupler.type_name() +
                     "' returned at t = " + std::to_string(observer.t_reached()) +
                     " s before time.end = " + std::to_string(t_end) + " s");
    }
    return {};
  } catch (const Interrupted& e) {
    return {RunStatus::kInterrupted, e.what()};
  } catch (const std::exception& e) {
    return {RunStatus::kFailed, e.what()};
  }
}

/// The soil the track's static state is found on: the scenario's, or the coupler's extra soil
/// declared with "track_statics" (abi.h, rumble_capabilities::participants_json).
SoilInstance& static_partner(RunComponents& c) {
  const auto declared =
      nlohmann::json::parse(c.coupler->type().capabilities.participants_json, nullptr, false);
  for (auto& [name, extra] : c.extras) {
    if (declared.is_object() && declared.contains(name) && declared[name].is_object() &&
        declared[name].value("track_statics", false))
      return *extra;
  }
  return *c.soil;
}

/// A coupler declaring RUMBLE_CAP_MONOLITHIC: the scenario's soil, from its linear matrices, is
/// integrated inside the track (decision 0008). Returns whether it was.
bool integrate_soil_if_asked(RunComponents& c) {
  if (!c.coupler->type().capabilities.has(RUMBLE_CAP_MONOLITHIC)) return false;
  c.track->integrate_soil(linear_soil(*c.soil, "coupler '" + c.coupler->type_name() + "'"));
  return true;
}

/// The soil's own statics u against its matrices' K^-1 B F, which the monolithic soil moves
/// about (abi.h linear_matrix): a soil may hold more statically than its matrices (the FEM
/// soil's static far field, docs/fem-soil.md section 3.2: a few per cent), which is logged; one
/// whose matrices miss a tenth of its settlement does not describe itself, and is refused.
void check_integrated_statics(const SoilInstance& soil, const TrackParticipant& track,
                              const std::vector<double>& u) {
  double beyond = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    beyond = std::max(beyond, std::abs(track.integrated_static_offset(i)));
    scale = std::max(scale, std::abs(u[i]));
  }
  std::ostringstream m;
  m << "soil '" << soil.type_name() << "': its statics hold the footprints up to " << beyond
    << " m beyond its linear matrices' K^-1 B F (largest settlement " << scale << " m)";
  if (beyond > 0.1 * scale) {
    m << "; its linear_matrix does not describe it, so it cannot be integrated with the track";
    throw RunError(m.str());
  }
  if (beyond > 1e-6 * scale)
    logger("engine")->info(
        "{} (a static far field beyond the matrices); the integrated soil "
        "moves about its own static state",
        m.str());
}

/// Static equilibrium of the track and its static partner (static_partner); the other soils
/// start from the same static footprint forces. Returns the track/soil iterations.
int solve_statics(RunComponents& c) {
  SoilInstance& partner = static_partner(c);
  const int iterations =
      c.track->solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
        partner.initialize(0.0, force, u);
      });
  const std::size_t n = c.track->interface_size();
  std::vector<double> force(n), u;
  c.track->footprint_forces(force.data());
  if (&partner != c.soil.get() || c.track->has_integrated_soil()) {
    c.soil->initialize(0.0, force, u);
  }
  if (c.track->has_integrated_soil()) check_integrated_statics(*c.soil, *c.track, u);
  for (auto& [name, extra] : c.extras)
    if (extra.get() != &partner) extra->initialize(0.0, force, u);
  return iterations;
}

}  // namespace

RunOutcome run_scenario(const scenario::RunSpec& spec, const PluginRegistry& registry,
                        ResultsDirectory& results, const RunOptions& options) {
  const auto log = logger("engine");
  const auto run_start = Clock::now();
  ExitGuard exit_guard;  // from the first plugin call: a constructor may call exit() too
  RunComponents c = build_components(spec, registry, options.built_soils);
  TrackParticipant& track = *c.track;

  RunOutcome outcome;
  outcome.results_dir = results.path();
  SummaryWriter summary(results, spec, c, options.heartbeat_seconds);
  exit_guard.watch(summary);
  const CrashRecord crash_record(summary);  // a plugin's segfault or abort() says so in it
  // Ctrl-C in a phase that cannot stop between its pieces (a dense LU, a plugin's long call)
  // ends the process at the deadline (core/interrupt.hpp); summary.json says so first.
  const LastWordScope last_word([&summary](const char* phase) {
    std::ostringstream m;
    m << "interrupted (" << interrupt_cause() << "): " << phase << " did not stop within "
      << kStopGraceSeconds << " s of the request, so the process ended there";
    summary.stopped_at_deadline(m.str());
    return exit_code(RunStatus::kInterrupted);
  });
  give_run_context(c, outcome.results_dir);

  // Anything failing from here on leaves summary.json saying so, then propagates.
  try {
    const bool integrated = integrate_soil_if_asked(c);
    const auto statics_start = Clock::now();
    int static_iterations = 0;
    try {
      const StopPhase phase("the static state");
      static_iterations = solve_statics(c);
    } catch (const std::exception&) {
      // A soil that honoured a stop request inside its static solve (a FEM soil's take tens of
      // seconds at a million DOFs) fails it: an interruption, not a failure.
      if (!interrupt_requested()) throw;
      throw Interrupted(std::string("interrupted (") + interrupt_cause() +
                        ") while the static state was solved, before the first step; "
                        "summary.json in " +
                        outcome.results_dir.string() + " says so");
    }
    const double statics_seconds = seconds_since(statics_start);
    nlohmann::json wheel_loads = nlohmann::json::array();
    for (std::size_t w = 0; w < track.vehicles().wheel_count(); ++w)
      wheel_loads.push_back(track.contact_force(w));
    log->info("static state: {} wheel(s), loads {} N, {} track/soil iteration(s)",
              track.vehicles().wheel_count(), wheel_loads.dump(), static_iterations);
    const double H = spec.macro_step;
    const double h = H / track.micro_steps(H);
    log->info("macro step {:.3g} s, track micro-step {:.3g} s ({} per macro step)", H, h,
              track.micro_steps(H));

    // ---- the participants
    TrackSide track_side(track);
    SoilSide soil_side("soil", *c.soil, track.interface_size(), integrated ? &track : nullptr);
    std::vector<std::unique_ptr<SoilSide>> extra_sides;
    std::vector<Participant*> participants{&track_side, &soil_side};
    std::vector<const SoilSide*> extras;
    for (auto& [name, extra] : c.extras) {
      extra_sides.push_back(std::make_unique<SoilSide>(name, *extra, track.interface_size()));
      participants.push_back(extra_sides.back().get());
      extras.push_back(extra_sides.back().get());
    }

    // ---- where the steps go
    RunRecorder recorder(results, track, soil_side, extras, c.receivers.distances,
                         c.receivers.surface);
    // Records of each participant: the initial state, every n-th step, and the last.
    recorder.reserve(static_cast<std::size_t>(std::ceil(spec.t_end / H)) / spec.outputs.every + 2);
    recorder.record_initial();
    std::unique_ptr<ProbeRecorder> probes;
    if (integrated && (c.receivers.probes || spec.outputs.field_interval)) {
      log->warn(
          "the soil is integrated with the track (monolithic): it records no receivers "
          "and writes no fields; its footprint motion is recorded");
    }
    if (c.receivers.probes && !integrated) {
      probes = std::make_unique<ProbeRecorder>(results, *c.soil, spec.outputs.receivers, spec.t_end,
                                               options.size_confirmed);
      probes->take();  // samples at t = 0, if the soil records one there
    }
    std::unique_ptr<FieldWriter> fields;
    if (spec.outputs.field_interval && c.soil->capabilities().has(RUMBLE_CAP_FIELD_OUTPUT) &&
        !integrated) {
      fields = std::make_unique<FieldWriter>(results, *c.soil, *spec.outputs.field_interval,
                                             spec.t_end, options.size_confirmed);
      fields->at(0.0);
    }

    // ---- the host and the coupler
    StepObserver observer(
        track, soil_side, extras, {recorder, probes.get(), fields.get(), &summary}, spec.t_end,
        spec.outputs.every, outcome.results_dir, options.progress, spec.divergence);
    double recording_seconds = 0.0;  // in the step callback: records, checks, heartbeat
    CosimHostImpl host(participants, c.coupler->type().abi_minor, [&](const StepOutcome& step) {
      const auto start = Clock::now();
      observer(step);
      recording_seconds += seconds_since(start);
    });
    std::string coupler_message;
    const StopPhase stepping("the time stepping");
    const rumble_status status = c.coupler->run(*host.table(), 0.0, spec.t_end, H, coupler_message);
    const Ending ending =
        judge(host, status, coupler_message, *c.coupler, observer, spec.t_end, outcome.results_dir);
    outcome.status = ending.status;
    outcome.message = ending.message;
    outcome.exit_code = exit_code(ending.status);
    if (ending.status != RunStatus::kFailed) finalize_components(c);  // stopped cleanly: flush

    // ---- the summary
    summary.set("time", {{"end", spec.t_end},
                         {"reached", observer.t_reached()},
                         {"macro_step", H},
                         {"macro_steps", observer.steps()},
                         {"micro_step", h}});
    // What is not in one of these is the coupler's own work (bench/coupling/coupler_cost.py).
    nlohmann::json wall = {{"total", seconds_since(run_start)},
                           {"statics", statics_seconds},
                           {"recording", recording_seconds},
                           {track_side.description(), track_side.wall_seconds},
                           {soil_side.description(), soil_side.wall_seconds}};
    for (const auto& side : extra_sides)
      wall[side->name() + " (" + side->description() + ")"] = side->wall_seconds;
    summary.set("wall_time_s", wall);
    summary.set("static", {{"wheel_loads_N", wheel_loads}, {"iterations", static_iterations}});
    // Per channel group, relative to the group's largest value over the run (run_residuals.hpp):
    // the velocity of an explicit scheme's held inputs lags the produced one by more than the
    // displacement does, which a single maximum over the groups would hide.
    const RunResiduals& residuals = observer.residuals();
    summary.set("interface", {{"max_relative_residual", residuals.largest_relative()},
                              {"max_relative_residual_by_group", residuals.relative()},
                              {"max_absolute_residual_by_group", residuals.absolute()},
                              {"energy_exchanged_J", recorder.energy_exchanged()},
                              {"track_energy_J", recorder.track_energy()},
                              {"energy_residual_J", recorder.energy_residual()}});
    summary.set("peak_footprint_velocity_m_s", recorder.peak_footprint_velocity());
    summary.set("footprint_velocity_definition",
                soil_side.reports_step_mean()
                    ? "mean over the macro step ending at each time, (u - u at its start) / H: "
                      "the coupler held the soil's force constant over the step"
                    : "the soil's velocity at the end of each macro step");
    summary.set("divergence", observer.divergence().summary());
    const double mean_iterations =
        observer.steps() > 0
            ? static_cast<double>(observer.iterations()) / static_cast<double>(observer.steps())
            : 0.0;
    summary.set("coupling",
                {{"discarded_steps", host.discards()},
                 {"partial_step_reports", observer.partial_reports()},
                 {"iterations",
                  {{"total", observer.iterations()},
                   {"mean_per_step", mean_iterations},
                   {"max_per_step", observer.max_iterations()}}},
                 {"unconverged_steps", observer.unconverged_steps()},
                 {"macro_step_s",
                  {{"shortest", observer.shortest_step()}, {"longest", observer.longest_step()}}}});
    nlohmann::json files = recorder.files();
    if (probes) {
      summary.set("ppv", probes->peaks());
      if (const std::string rule = probes->resolution_rule(); !rule.empty())
        summary.set("resolved_band_rule", rule);
      files.push_back(probes->file());
    }
    if (c.receivers.surface) {
      nlohmann::json ppv = nlohmann::json::array();
      for (std::size_t r = 0; r < c.receivers.distances.size(); ++r)
        ppv.push_back({{"distance_m", c.receivers.distances[r]},
                       {"ppv_m_s", recorder.peak_receiver_velocity()[r]}});
      summary.set("ppv", ppv);
    }
    if (fields) {
      files.push_back(fields->index_file());
      summary.set("field_snapshots", fields->snapshots());
    }
    summary.set("files", files);
    summary.finish(outcome.status, outcome.message);
  } catch (const Interrupted& e) {
    summary.fail(e.what(), RunStatus::kInterrupted);
    throw;
  } catch (const std::exception& e) {
    summary.fail(e.what());
    throw;
  }
  return outcome;
}

}  // namespace rumble
