#include "run/run_scenario.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <vector>

#include "core/cpu_affinity.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"
#include "core/peak_memory.hpp"
#include "run/core_share.hpp"
#include "run/cosim_host.hpp"
#include "run/crash_record.hpp"
#include "run/field_writer.hpp"
#include "run/memory_account.hpp"
#include "run/participant.hpp"
#include "run/probe_recorder.hpp"
#include "run/run_components.hpp"
#include "run/run_recorder.hpp"
#include "run/run_statics.hpp"
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

/// What a Ctrl-C that a phase could not honour in time leaves: summary.json says the process
/// ended at the deadline (core/interrupt.hpp), and the exit code is an interruption's.
LastWord deadline_last_word(SummaryWriter& summary) {
  return [&summary](const char* phase) {
    std::ostringstream m;
    m << "interrupted (" << interrupt_cause() << "): " << phase << " did not stop within "
      << kStopGraceSeconds << " s of the request, so the process ended there";
    summary.stopped_at_deadline(m.str());
    return exit_code(RunStatus::kInterrupted);
  };
}

/// The track's micro-step within the macro step H [s], logged with H.
double announce_micro_step(TrackParticipant& track, double H) {
  const double h = H / track.micro_steps(H);
  logger("engine")->info("macro step {:.3g} s, track micro-step {:.3g} s ({} per macro step)", H, h,
                         track.micro_steps(H));
  return h;
}

/// The participants the coupler steps: the track, the scenario's soil (moved by the track when
/// it is integrated there) and the coupler's extra soils.
struct Sides {
  Sides(RunComponents& c, bool integrated)
      : track(*c.track),
        static_force(static_forces(*c.track)),
        soil("soil", *c.soil, static_force, integrated ? c.track.get() : nullptr) {
    for (auto& [name, extra] : c.extras) {
      extra_sides.push_back(std::make_unique<SoilSide>(name, *extra, static_force));
      participants.push_back(extra_sides.back().get());
      extras.push_back(extra_sides.back().get());
    }
  }
  Sides(const Sides&) = delete;
  Sides& operator=(const Sides&) = delete;

  /// The track's footprint forces [N] now: after the statics, those every soil was initialized
  /// under (run/run_statics.hpp).
  static std::vector<double> static_forces(const TrackParticipant& track) {
    std::vector<double> f(track.interface_size());
    track.footprint_forces(f.data());
    return f;
  }

  TrackSide track;
  std::vector<double> static_force;  // N
  SoilSide soil;
  std::vector<std::unique_ptr<SoilSide>> extra_sides;
  std::vector<Participant*> participants{&track, &soil};
  std::vector<const SoilSide*> extras;
};

/// Where the steps go: the participants' records (the initial state, every n-th step and the
/// last), the soil's receivers and its field snapshots, each starting at t = 0.
struct Recording {
  Recording(const scenario::RunSpec& spec, const RunOptions& options, RunComponents& c,
            ResultsDirectory& results, const Sides& sides, bool integrated)
      : recorder(results, *c.track, sides.soil, sides.extras, c.receivers.distances,
                 c.receivers.surface) {
    recorder.reserve(
        static_cast<std::size_t>(std::ceil(spec.t_end / spec.macro_step)) / spec.outputs.every + 2);
    recorder.record_initial();
    if (integrated && (c.receivers.probes || spec.outputs.field_interval)) {
      logger("engine")->warn(
          "the soil is integrated with the track (monolithic): it records no receivers "
          "and writes no fields; its footprint motion is recorded");
    }
    if (c.receivers.probes && !integrated) {
      probes = std::make_unique<ProbeRecorder>(results, *c.soil, spec.outputs.receivers, spec.t_end,
                                               options.size_confirmed);
      probes->take();  // samples at t = 0, if the soil records one there
    }
    if (spec.outputs.field_interval && c.soil->capabilities().has(RUMBLE_CAP_FIELD_OUTPUT) &&
        !integrated) {
      fields = std::make_unique<FieldWriter>(results, *c.soil, *spec.outputs.field_interval,
                                             spec.t_end, options.size_confirmed);
      fields->at(0.0);
    }
  }

  RunRecorder recorder;
  std::unique_ptr<ProbeRecorder> probes;
  std::unique_ptr<FieldWriter> fields;
};

/// Where the wall time went. What is not in one of these is the coupler's own work
/// (bench/coupling/coupler_cost.py).
nlohmann::json wall_times(Clock::time_point run_start, double statics_seconds,
                          double recording_seconds, const Sides& sides) {
  nlohmann::json wall = {{"total", seconds_since(run_start)},
                         {"statics", statics_seconds},
                         {"recording", recording_seconds},
                         {sides.track.description(), sides.track.wall_seconds},
                         {sides.soil.description(), sides.soil.wall_seconds}};
  for (const auto& side : sides.extra_sides)
    wall[side->name() + " (" + side->description() + ")"] = side->wall_seconds;
  return wall;
}

/// summary.json's account of the coupling: the interface's residuals and energies, the footprint
/// velocities, the divergence watch and the coupler's iterations and steps.
void summarize_coupling(SummaryWriter& summary, const StepObserver& observer,
                        const CosimHostImpl& host, const RunRecorder& recorder,
                        const SoilSide& soil_side) {
  // Per channel group, relative to the group's largest value over the run (run_residuals.hpp):
  // the velocity of an explicit scheme's held inputs lags the produced one by more than the
  // displacement does, which a single maximum over the groups would hide.
  // The predictor's residuals: the coupling error, of the scheme's order (docs/couplers.md).
  const RunResiduals& residuals = observer.residuals();
  const RunResiduals& predictor = observer.predictor_residuals();
  summary.set("interface", {{"max_relative_residual", residuals.largest_relative()},
                            {"max_relative_residual_by_group", residuals.relative()},
                            {"predictor_relative_residual", predictor.largest_relative()},
                            {"predictor_relative_residual_by_group", predictor.relative()},
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
  const double mean_iterations = observer.steps() > 0 ? static_cast<double>(observer.iterations()) /
                                                            static_cast<double>(observer.steps())
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
}

/// summary.json's receivers' peaks, field snapshots and the files the run wrote.
void summarize_outputs(SummaryWriter& summary, const ReceiverSetup& receivers,
                       const Recording& rec) {
  nlohmann::json files = rec.recorder.files();
  if (rec.probes) {
    summary.set("ppv", rec.probes->peaks());
    if (const std::string rule = rec.probes->resolution_rule(); !rule.empty())
      summary.set("resolved_band_rule", rule);
    files.push_back(rec.probes->file());
  }
  if (receivers.surface) {
    nlohmann::json ppv = nlohmann::json::array();
    for (std::size_t r = 0; r < receivers.distances.size(); ++r)
      ppv.push_back({{"distance_m", receivers.distances[r]},
                     {"ppv_m_s", rec.recorder.peak_receiver_velocity()[r]}});
    summary.set("ppv", ppv);
  }
  if (rec.fields) {
    files.push_back(rec.fields->index_file());
    summary.set("field_snapshots", rec.fields->snapshots());
  }
  summary.set("files", files);
}

/// The run's start, its static equilibrium and its memory so far, for the summary.
struct RunSoFar {
  Clock::time_point start;
  bool integrated = false;
  const StaticState& statics;
  RunMemory& memory;                                   // every rank's peaks per phase
  const std::optional<SoilInstance::Size>& soil_size;  // ABI 1.5: DOFs and estimate
};

/// The soils' threads for the steps to come (run/core_share.hpp).
void grant_soils(RunComponents& c, unsigned threads) {
  c.soil->grant_threads(threads);
  for (auto& [name, extra] : c.extras) extra->grant_threads(threads);
}

/// The coupled time stepping from t = 0 to time.end in macro steps, every step recorded and
/// watched; the outcome judged and summary.json completed with what the run measured.
void co_simulate(const scenario::RunSpec& spec, const RunOptions& options, RunComponents& c,
                 ResultsDirectory& results, SummaryWriter& summary, const RunSoFar& so_far,
                 RunOutcome& outcome) {
  const double H = spec.macro_step;
  const double h = announce_micro_step(*c.track, H);
  Sides sides(c, so_far.integrated);
  Recording rec(spec, options, c, results, sides, so_far.integrated);
  StepObserver observer(*c.track, sides.soil, sides.extras,
                        {rec.recorder, rec.probes.get(), rec.fields.get(), &summary}, spec.t_end,
                        spec.outputs.every, outcome.results_dir, options.progress, spec.divergence);
  double recording_seconds = 0.0;  // in the step callback: records, checks, heartbeat
  CoreShare cores(static_cast<unsigned>(usable_cpus()),
                  c.coupler->capabilities().has(RUMBLE_CAP_THREADS));
  grant_soils(c, cores.first_grant());
  CosimHostImpl host(
      sides.participants, c.track->footprints(), c.coupler->type().abi_minor,
      [&](const StepOutcome& step) {
        const auto start = Clock::now();
        observer(step);
        recording_seconds += seconds_since(start);
        // Between steps: no participant is advancing (the grant is read by the
        // soil at its next advance).
        if (const unsigned threads = cores.after_step(
                sides.track.wall_seconds, sides.soil.wall_seconds, host.take_overlap())) {
          grant_soils(c, threads);
          logger("engine")->info("the soil steps on {} thread(s): {}", threads, cores.reason());
        }
      });
  std::string coupler_message;
  const StopPhase stepping("the time stepping");
  const rumble_status status = c.coupler->run(*host.table(), 0.0, spec.t_end, H, coupler_message);
  so_far.memory.end("stepping");
  const Ending ending =
      judge(host, status, coupler_message, *c.coupler, observer, spec.t_end, outcome.results_dir);
  outcome.status = ending.status;
  outcome.message = ending.message;
  outcome.exit_code = exit_code(ending.status);
  if (ending.status != RunStatus::kFailed) finalize_components(c);  // stopped cleanly: flush

  summary.set("time", {{"end", spec.t_end},
                       {"reached", observer.t_reached()},
                       {"macro_step", H},
                       {"macro_steps", observer.steps()},
                       {"micro_step", h}});
  summary.set("wall_time_s",
              wall_times(so_far.start, so_far.statics.seconds, recording_seconds, sides));
  summary.set("static", {{"wheel_loads_N", so_far.statics.wheel_loads},
                         {"iterations", so_far.statics.iterations}});
  summary.set("memory", memory_summary(so_far.memory, so_far.soil_size));
  log_memory(so_far.memory, so_far.soil_size);
  summarize_coupling(summary, observer, host, rec.recorder, sides.soil);
  summarize_outputs(summary, c.receivers, rec);
  summary.finish(outcome.status, outcome.message);
}

}  // namespace

RunOutcome run_scenario(const scenario::RunSpec& spec, const PluginRegistry& registry,
                        ResultsDirectory& results, const RunOptions& options) {
  const auto run_start = Clock::now();
  ExitGuard exit_guard;  // from the first plugin call: a constructor may call exit() too
  RunMemory memory;
  RunComponents c = build_components(spec, registry, options.built_soils);
  memory.end("build");

  RunOutcome outcome;
  outcome.results_dir = results.path();
  SummaryWriter summary(results, spec, c, options.heartbeat_seconds);
  exit_guard.watch(summary);
  const CrashRecord crash_record(summary);  // a plugin's segfault or abort() says so in it
  // Ctrl-C in a phase that cannot stop between its pieces (a dense LU, a plugin's long call)
  // ends the process at the deadline (core/interrupt.hpp); summary.json says so first.
  const LastWordScope last_word(deadline_last_word(summary));
  give_run_context(c, outcome.results_dir);

  // Anything failing from here on leaves summary.json saying so, then propagates.
  try {
    const bool integrated = integrate_soil_if_asked(c);
    const std::optional<SoilInstance::Size> soil_size = announce_soil_size(*c.soil);
    const StaticState statics = static_equilibrium(c, outcome.results_dir);
    memory.end("statics");
    co_simulate(spec, options, c, results, summary,
                {run_start, integrated, statics, memory, soil_size}, outcome);
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
