#include "run/run_scenario.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"
#include "plugin/instance.hpp"
#include "run/cosim_host.hpp"
#include "run/field_writer.hpp"
#include "run/participant.hpp"
#include "run/probe_recorder.hpp"
#include "run/run_recorder.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A footprint displacement beyond this [m] is not ground vibration: the coupled solution
// has blown up (typically an unstable explicit coupling with too large a macro step).
constexpr double kDivergedDisplacement = 1.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// summary.json is replaced atomically (write + rename), so it is never half-written.
void write_summary(const fs::path& dir, const nlohmann::json& summary) {
  const fs::path tmp = dir / "summary.json.tmp";
  {
    std::ofstream out(tmp);
    out << summary.dump(2) << '\n';
    if (!out) {
      throw RunError("cannot write " + (dir / "summary.json").string() +
                     "; check free disk space and that outputs.directory is writable");
    }
  }
  fs::rename(tmp, dir / "summary.json");
}

const ComponentType& resolve(const PluginRegistry& registry, rumble_kind kind,
                             const nlohmann::json& component, const std::string& pointer) {
  const std::string type = component.at("type").get<std::string>();
  const ComponentType* t = registry.find(kind, type);
  if (t == nullptr) {
    throw ConfigError(pointer + "/type: unknown " + kind_name(kind) + " type '" + type +
                      "'; run `rumble plugins` to list the known types");
  }
  return *t;
}

/// Threads an instance may use: all cores, less one for the track when the coupler runs
/// participants at once (it declares RUMBLE_CAP_THREADS, as jacobi does).
unsigned soil_threads(const CouplerInstance& coupler) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return coupler.capabilities().has(RUMBLE_CAP_THREADS) ? std::max(1u, cores - 1) : cores;
}

/// Throws RunError when the interface values show the coupled solution has blown up.
void check_finite(const TrackParticipant& track, const SoilSide& soil, double t,
                  std::vector<double>& scratch) {
  const std::size_t n = track.interface_size();
  scratch.resize(std::max(scratch.size(), 2 * n));
  soil.get_output(scratch.data());
  for (std::size_t i = 0; i < n; ++i) {
    const double u = scratch[i];
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
  for (std::size_t w = 0; w < track.vehicles().wheel_count(); ++w) {
    if (!std::isfinite(track.contact_force(w))) {
      std::ostringstream m;
      m << "simulation diverged at t = " << t << " s: contact force of wheel " << w
        << " is not finite; reduce time.macro_step or track.integrator.micro_step";
      throw RunError(m.str());
    }
  }
}

class ProgressLine {
 public:
  ProgressLine(bool enabled, double t_end) : enabled_(enabled), t_end_(t_end) {}
  void update(double t) {
    if (!enabled_) return;
    const double elapsed = seconds_since(start_);
    if (elapsed - last_ < 0.25 && t < t_end_) return;
    last_ = elapsed;
    const double fraction = std::min(1.0, t / t_end_);
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r  t = %.4f / %.4f s  %3.0f%%  elapsed %.1f s  ETA %.1f s   ", t, t_end_,
                 100.0 * fraction, elapsed, eta);
    std::fflush(stderr);
    shown_ = true;
  }
  ~ProgressLine() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  double t_end_;
  Clock::time_point start_ = Clock::now();
  double last_ = -1.0;
  bool shown_ = false;
};

}  // namespace

fs::path results_directory(const nlohmann::json& scenario, const fs::path& scenario_path) {
  const fs::path dir = scenario.at("outputs").at("directory").get<std::string>();
  return dir.is_absolute() ? dir : scenario_path.parent_path() / dir;
}

RunOutcome run_scenario(const nlohmann::json& scenario, const fs::path& scenario_path,
                        const PluginRegistry& registry, const RunOptions& options) {
  const auto log = logger("engine");
  const auto run_start = Clock::now();
  const fs::path scenario_dir = scenario_path.parent_path();
  const double t_end = scenario.at("time").at("end").get<double>();
  const double H = scenario.at("time").at("macro_step").get<double>();

  // ---- participants
  VehicleSet vehicles;
  const auto& vj = scenario.at("vehicles");
  for (std::size_t i = 0; i < vj.size(); ++i) {
    const std::string ptr = "/vehicles/" + std::to_string(i);
    const ComponentType& type = resolve(registry, RUMBLE_KIND_VEHICLE, vj[i], ptr);
    auto instance = std::make_unique<VehicleInstance>(
        type, ptr, vj[i].value("params", nlohmann::json::object()), scenario_dir);
    vehicles.add(std::move(instance), vj[i].value("name", "vehicle" + std::to_string(i)),
                 vj[i].at("speed").get<double>(), vj[i].at("start").get<double>());
  }
  const TrackConfig track_config = TrackConfig::from_json(scenario.at("track"));
  TrackParticipant track(track_config, std::move(vehicles));
  const auto& sj = scenario.at("soil");
  SoilInstance soil(resolve(registry, RUMBLE_KIND_SOIL, sj, "/soil"), "/soil",
                    sj.value("params", nlohmann::json::object()), scenario_dir);
  soil.accept_layout(track.footprints());
  const auto& cj = scenario.at("coupling");
  CouplerInstance coupler(resolve(registry, RUMBLE_KIND_COUPLER, cj, "/coupling"), "/coupling",
                          cj.value("params", nlohmann::json::object()), scenario_dir);
  // The coupler's extra participants (ABI 1.1), each a soil on the same footprints.
  std::vector<std::pair<std::string, std::unique_ptr<SoilInstance>>> extras;
  const nlohmann::json extra_components = cj.value("participants", nlohmann::json::object());
  for (const auto& [name, component] : extra_components.items()) {
    const std::string ptr = "/coupling/participants/" + name;
    extras.emplace_back(name,
                        std::make_unique<SoilInstance>(
                            resolve(registry, RUMBLE_KIND_SOIL, component, ptr), ptr,
                            component.value("params", nlohmann::json::object()), scenario_dir));
    extras.back().second->accept_layout(track.footprints());
  }

  const auto& outputs = scenario.at("outputs");
  const double x_mid = 0.5 * (track_config.sleeper_count - 1) * track_config.sleeper_spacing;
  const std::vector<ReceiverPoint> receivers = receiver_points(outputs, x_mid);
  std::vector<double> distances;  // ABI 1.0 receivers: surface points at x_mid only
  bool receivers_offered = false, probes_offered = false;
  if (!receivers.empty()) {
    std::vector<rumble_probe> probes;
    for (const ReceiverPoint& r : receivers) probes.push_back({r.name.c_str(), r.x, r.y, r.depth});
    probes_offered = soil.set_probes(probes, outputs.value("receiver_interval", 0.0));
    if (!probes_offered) {
      std::vector<rumble_receiver> points;
      for (const ReceiverPoint& r : receivers) {
        if (r.depth == 0.0 && r.x == x_mid) {
          points.push_back({r.x, r.y});
          distances.push_back(r.y);
        }
      }
      receivers_offered = !points.empty() && soil.set_receivers(points);
    }
    if (!probes_offered && !receivers_offered) {
      log->warn(
          "/outputs/receivers: soil type '{}' offers no receivers; the receivers are ignored "
          "(footprint motions are still recorded)",
          soil.type_name());
    }
  }

  // ---- results directory and the first summary
  RunOutcome outcome;
  outcome.results_dir = results_directory(scenario, scenario_path);
  std::error_code ec;
  fs::create_directories(outcome.results_dir, ec);
  if (ec) {
    throw RunError("cannot create results directory " + outcome.results_dir.string() + ": " +
                   ec.message() + "; set /outputs/directory to a writable place");
  }
  nlohmann::json summary;
  summary["rumble_version"] = RUMBLE_VERSION;
  summary["scenario_file"] = fs::absolute(scenario_path).string();
  summary["scenario"] = scenario;
  summary["status"] = "running";
  nlohmann::json plugins = nlohmann::json::array();
  for (const Instance* inst : std::initializer_list<const Instance*>{&soil, &coupler}) {
    const auto* d = inst->type().library->descriptor;
    plugins.push_back({{"type", inst->type_name()},
                       {"kind", kind_name(inst->type().kind)},
                       {"plugin", d->plugin_name},
                       {"version", d->plugin_version},
                       {"path", inst->type().library->path.string()}});
  }
  for (const auto& v : track.vehicles().vehicles()) {
    const auto* d = v.instance->type().library->descriptor;
    plugins.push_back({{"type", v.instance->type_name()},
                       {"kind", "vehicle"},
                       {"plugin", d->plugin_name},
                       {"version", d->plugin_version},
                       {"path", v.instance->type().library->path.string()}});
  }
  summary["plugins"] = plugins;
  write_summary(outcome.results_dir, summary);
  const unsigned threads = soil_threads(coupler);
  soil.set_run_context(outcome.results_dir, threads);
  for (auto& [name, extra] : extras) extra->set_run_context(outcome.results_dir, threads);
  coupler.set_run_context(outcome.results_dir, 1);

  // Anything failing from here on leaves summary.json saying so, then propagates.
  try {
    // ---- static equilibrium, then the coupled run
    const auto statics_start = Clock::now();
    const int static_iterations =
        track.solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
          soil.initialize(0.0, force, u);
        });
    if (!extras.empty()) {  // the extra soils start from the same static footprint forces
      std::vector<double> force(track.interface_size()), u;
      track.footprint_forces(force.data());
      for (auto& [name, extra] : extras) extra->initialize(0.0, force, u);
    }
    const double statics_seconds = seconds_since(statics_start);
    nlohmann::json wheel_loads = nlohmann::json::array();
    for (std::size_t w = 0; w < track.vehicles().wheel_count(); ++w)
      wheel_loads.push_back(track.contact_force(w));
    log->info("static state: {} wheel(s), loads {} N, {} track/soil iteration(s)",
              track.vehicles().wheel_count(), wheel_loads.dump(), static_iterations);
    const double h = H / std::ceil(H / track.micro_step_limit() - 1e-9);
    log->info("macro step {:.3g} s, track micro-step {:.3g} s ({} per macro step)", H, h,
              static_cast<int>(std::lround(H / h)));

    RunRecorder recorder(outcome.results_dir, track, soil, distances, receivers_offered);
    recorder.record(0.0, 0.0, 0.0);
    std::unique_ptr<ProbeRecorder> probe_recorder;
    if (probes_offered) {
      probe_recorder = std::make_unique<ProbeRecorder>(outcome.results_dir, soil, receivers);
      probe_recorder->take();  // samples at t = 0, if the soil records one there
    }
    std::unique_ptr<FieldWriter> fields;
    if (outputs.contains("fields") && soil.capabilities().has(RUMBLE_CAP_FIELD_OUTPUT)) {
      fields = std::make_unique<FieldWriter>(outcome.results_dir, soil,
                                             outputs.at("fields").at("interval").get<double>());
      fields->at(0.0);
    }
    TrackSide track_side(track);
    SoilSide soil_side("soil", soil, track.interface_size());
    std::vector<std::unique_ptr<SoilSide>> extra_sides;
    std::vector<Participant*> participants{&track_side, &soil_side};
    for (auto& [name, extra] : extras) {
      extra_sides.push_back(std::make_unique<SoilSide>(name, *extra, track.interface_size()));
      participants.push_back(extra_sides.back().get());
    }
    double t_reached = 0.0, t_recorded = 0.0;
    std::size_t steps = 0;
    const std::size_t every = outputs.value("every", std::size_t{1});
    std::vector<double> scratch;
    ProgressLine progress(options.progress, t_end);
    std::size_t partial_reports = 0;
    CosimHostImpl host(participants, coupler.type().abi_minor, [&](const StepOutcome& step) {
      const double t = step.t;
      // The recorder reads the track and the soil together: a step counts once final for both.
      // (Schemes that finish participants at different times, as two-step will, need a
      // recorder per participant; until then their partial reports are only counted.)
      if (!step.final_for(RUMBLE_PARTICIPANT_TRACK) || !step.final_for(RUMBLE_PARTICIPANT_SOIL)) {
        ++partial_reports;
        return;
      }
      t_reached = t + step.H;
      ++steps;
      if (probe_recorder) probe_recorder->take();
      if (fields) fields->at(t_reached);
      if (steps % every == 0 || t_reached >= t_end * (1.0 - 1e-12)) {
        recorder.record(t_reached, t_reached - t_recorded, step.max_relative_residual());
        t_recorded = t_reached;
      }
      check_finite(track, soil_side, t + step.H, scratch);
      if (interrupt_requested()) {
        std::ostringstream m;
        m << "interrupted at t = " << t + step.H << " s (Ctrl-C); results up to that time are in "
          << outcome.results_dir.string();
        throw Interrupted(m.str());
      }
      progress.update(t + step.H);
    });

    std::string coupler_message;
    const rumble_status status = coupler.run(*host.table(), 0.0, t_end, H, coupler_message);
    outcome.status = "completed";
    try {
      // A plugin that honoured a stop request inside its step returns ERROR: an interruption
      // too, not a failure (the host's own Interrupted, raised between steps, passes as it is).
      const auto interrupted_inside_step = [&] {
        std::ostringstream m;
        m << "interrupted (Ctrl-C) inside the step after t = " << t_reached
          << " s; results up to that time are in " << outcome.results_dir.string();
        return Interrupted(m.str());
      };
      try {
        host.rethrow_if_failed();
      } catch (const Interrupted&) {
        throw;
      } catch (const std::exception&) {
        if (interrupt_requested()) throw interrupted_inside_step();
        throw;
      }
      if (status != RUMBLE_OK && interrupt_requested()) throw interrupted_inside_step();
      if (status == RUMBLE_ERROR || status == RUMBLE_FATAL) {
        throw RunError("coupler '" + coupler.type_name() + "' failed: " + coupler_message);
      }
      if (t_reached < t_end - 1e-9 * t_end) {
        throw RunError("coupler '" + coupler.type_name() +
                       "' returned at t = " + std::to_string(t_reached) +
                       " s before time.end = " + std::to_string(t_end) + " s");
      }
    } catch (const Interrupted& e) {
      outcome.status = "interrupted";
      outcome.message = e.what();
    } catch (const std::exception& e) {
      outcome.status = "failed";
      outcome.message = e.what();
    }
    outcome.exit_code = outcome.status == "completed" ? 0 : 3;
    if (outcome.status != "failed") {  // a run that stopped cleanly: let plugins flush
      coupler.finalize();
      soil.finalize();
      for (auto& [name, extra] : extras) extra->finalize();
    }

    summary["status"] = outcome.status;
    if (!outcome.message.empty()) summary["message"] = outcome.message;
    summary["time"] = {{"end", t_end},
                       {"reached", t_reached},
                       {"macro_step", H},
                       {"macro_steps", steps},
                       {"micro_step", h}};
    summary["wall_time_s"] = {{"total", seconds_since(run_start)},
                              {"statics", statics_seconds},
                              {track_side.description(), track_side.wall_seconds},
                              {soil_side.description(), soil_side.wall_seconds}};
    for (const auto& side : extra_sides)
      summary["wall_time_s"][side->name() + " (" + side->description() + ")"] = side->wall_seconds;
    summary["static"] = {{"wheel_loads_N", wheel_loads}, {"iterations", static_iterations}};
    summary["interface"] = {{"max_relative_residual", recorder.max_residual()},
                            {"energy_exchanged_J", recorder.energy_exchanged()}};
    summary["peak_footprint_velocity_m_s"] = recorder.peak_footprint_velocity();
    summary["coupling"] = {{"discarded_steps", host.discards()},
                           {"partial_step_reports", partial_reports}};
    if (probe_recorder) summary["ppv"] = probe_recorder->peaks();
    if (receivers_offered) {
      nlohmann::json ppv = nlohmann::json::array();
      for (std::size_t r = 0; r < distances.size(); ++r)
        ppv.push_back(
            {{"distance_m", distances[r]}, {"ppv_m_s", recorder.peak_receiver_velocity()[r]}});
      summary["ppv"] = ppv;
    }
    summary["files"] = recorder.files();
    if (probe_recorder) summary["files"].push_back(probe_recorder->file());
    if (fields) {
      summary["files"].push_back(fields->index_file());
      summary["field_snapshots"] = fields->snapshots();
    }
    write_summary(outcome.results_dir, summary);
  } catch (const std::exception& e) {
    summary["status"] = "failed";
    summary["message"] = e.what();
    try {
      write_summary(outcome.results_dir, summary);
    } catch (const std::exception&) {
      // The disk refused the summary too; the original error is the one to report.
    }
    throw;
  }
  return outcome;
}

}  // namespace rumble
