// template_coupler_test: the built template_coupler library, loaded the way the engine loads it
// (dlopen, the one exported entry point, the C function table), run against a stand-in host
// (the ABI 1.1 rumble_cosim_host) whose two participants are linear and static, so that the
// coupled answer of Gauss-Seidel order 0 is known in closed form:
//   track: F = a - b u   (u [m]: the footprint displacement it was given, held over the step)
//   soil:  u = F / s     (F [N]: the footprint force it was given, held over the step)
//          v = (u - u_before) / h  [m/s], over the step of length h
// Per final step u_{k+1} = (a - b u_k) / s, so u_k = u* + (u_0 - u*) r^k with u* = a / (s + b)
// and r = -b / s, whatever the steps' lengths. The soil's outputs are velocity then
// displacement (the engine's soils give displacement first): the coupler must match channels by
// group name. Each participant checks that it advances from where it is, so a participant not
// put back after a refused step is caught.
//
// Two parts, for whoever turns this template into another scheme: the contract every coupler
// keeps with the host whatever its scheme (keeps_the_contract: the run ends at its end on both
// sides, one report per final step with no gap, every checkpoint freed, a refused step retried
// shorter or the run stopped with a message), which stays; and this template's own scheme,
// Gauss-Seidel of order 0, checked against its closed form and its order of calls (the
// functions after "This template's scheme"), which a new scheme replaces with its own answers.
// The stand-in lets either participant save and restore its state, as the engine's do.
// Standard C++17 and the SDK headers only: no test framework, no engine. `ctest` runs it with
// the library's path as the argument; it prints each failed check and exits non-zero when there
// is one.
#include <dlfcn.h>
#include <rumble/abi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr const char* kType = "template_coupler";
constexpr std::size_t kFootprints = 2;
constexpr double kLoad[kFootprints] = {1.0e5, 6.0e4};          // a [N]
constexpr double kTrackStiffness = 3.0e7;                      // b [N/m]
constexpr double kSoilStiffness = 1.0e8;                       // s [N/m]
constexpr double kStart = 0.0, kEnd = 0.0105, kStep = 1.0e-3;  // 11 macro steps, the last 0.5 ms
constexpr std::uint32_t kTrack = RUMBLE_PARTICIPANT_TRACK, kSoil = RUMBLE_PARTICIPANT_SOIL;

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    ++failures;
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
  }
}

void check_close(double actual, double expected, double relative, const std::string& what) {
  check(std::abs(actual - expected) <= relative * std::abs(expected),
        what + ": " + std::to_string(actual) + " instead of " + std::to_string(expected));
}

/// The factory of `type` in the library at `path`, or null with the reason printed. The library
/// stays loaded for the rest of the process, as the engine keeps it.
const rumble_factory* load_factory(const char* path, int kind, const char* type) {
  void* library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    std::fprintf(stderr, "cannot load %s: %s\n", path, dlerror());
    return nullptr;
  }
  void* symbol = dlsym(library, RUMBLE_PLUGIN_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    std::fprintf(stderr, "%s exports no %s\n", path, RUMBLE_PLUGIN_ENTRY_SYMBOL);
    return nullptr;
  }
  rumble_plugin_entry_fn entry = nullptr;
  std::memcpy(&entry, &symbol, sizeof entry);  // object to function pointer, as dlsym needs
  const rumble_plugin_descriptor* d = entry();
  for (std::uint64_t i = 0; i < d->n_factories; ++i) {
    const rumble_factory& f = d->factories[i];
    if (f.kind == kind && std::strcmp(f.type_name, type) == 0) return &f;
  }
  std::fprintf(stderr, "%s provides no type '%s' of kind %d\n", path, type, kind);
  return nullptr;
}

// Channel groups, as the engine names them. Track outputs: forces. Track inputs: displacement
// then velocity. Soil outputs: velocity then displacement (deliberately). Soil inputs: forces.
const rumble_channel_group kTrackOutputs[] = {{"footprint_force", "N", 0, kFootprints}};
const rumble_channel_group kTrackInputs[] = {
    {"footprint_displacement", "m", 0, kFootprints},
    {"footprint_velocity", "m/s", kFootprints, kFootprints}};
const rumble_channel_group kSoilOutputs[] = {
    {"footprint_velocity", "m/s", 0, kFootprints},
    {"footprint_displacement", "m", kFootprints, kFootprints}};
const rumble_channel_group kSoilInputs[] = {{"footprint_force", "N", 0, kFootprints}};
constexpr std::size_t kVelocity = 0, kDisplacement = kFootprints;  // offsets in soil outputs

/// One final step as the coupler reported it.
struct Report {
  double t = 0.0, H = 0.0;
  std::uint32_t iterations = 0;
  bool converged = false;
  std::uint64_t participants = ~std::uint64_t{0};
  std::vector<std::string> groups;
  std::vector<double> absolute, relative;
};

/// The host side of a run: the two stand-in participants and a record of the coupler's calls.
struct StandIn {
  // Participants' state: time [s] and outputs.
  double track_time = kStart, soil_time = kStart;
  std::vector<double> force = std::vector<double>(kFootprints, 0.0);            // track outputs
  std::vector<double> motion = std::vector<double>(2 * kFootprints, 0.0);       // soil: v, u
  std::vector<double> track_input = std::vector<double>(2 * kFootprints, 0.0);  // u, v
  std::vector<double> soil_input = std::vector<double>(kFootprints, 0.0);       // F
  // Refusals: a participant refuses (DISCARD) any step longer than its limit [s].
  double track_max_step = 1.0, soil_max_step = 1.0;
  bool track_checkpoints = true, soil_checkpoints = true;
  // The checkpoints: time and outputs per slot, per participant (track, soil).
  std::array<double, RUMBLE_CHECKPOINT_SLOTS> saved_time{}, saved_soil_time{};
  std::array<std::vector<double>, RUMBLE_CHECKPOINT_SLOTS> saved_force{}, saved_motion{};
  std::array<std::array<bool, RUMBLE_CHECKPOINT_SLOTS>, 2> held{};  // saved and not yet freed
  // Record.
  std::string calls;  // per advance: 'T' / 'S' (taken), 't' / 's' (refused); per restore 'R'
                      // (track) or 'Q' (soil)
  int saves = 0, frees = 0;
  std::vector<Report> reports;

  static StandIn& of(void* ctx) { return *static_cast<StandIn*>(ctx); }

  bool can_save(std::uint32_t p, std::uint32_t slot) const {
    const bool can = p == kTrack ? track_checkpoints : p == kSoil && soil_checkpoints;
    return can && slot < RUMBLE_CHECKPOINT_SLOTS;
  }
  bool holds_a_checkpoint() const {
    for (const auto& slots : held)
      for (const bool h : slots)
        if (h) return true;
    return false;
  }

  static rumble_status groups(const rumble_channel_group* groups, std::uint64_t count,
                              rumble_channel_group* out, std::uint64_t capacity, std::uint64_t* n) {
    *n = count;
    for (std::uint64_t i = 0; i < count && i < capacity; ++i) out[i] = groups[i];
    return RUMBLE_OK;
  }

  rumble_status advance_track(double t, double h) {
    check(std::abs(t - track_time) < 1e-12,
          "the track advances from where it is (t = " + std::to_string(t) + " s, it is at " +
              std::to_string(track_time) + " s)");
    if (h > track_max_step) {
      calls += 't';
      return RUMBLE_DISCARD;
    }
    calls += 'T';
    for (std::size_t i = 0; i < kFootprints; ++i)
      force[i] = kLoad[i] - kTrackStiffness * track_input[i];
    track_time = t + h;
    return RUMBLE_OK;
  }

  rumble_status advance_soil(double t, double h) {
    check(std::abs(t - soil_time) < 1e-12, "the soil advances from where it is");
    if (h > soil_max_step) {
      calls += 's';
      return RUMBLE_DISCARD;
    }
    calls += 'S';
    for (std::size_t i = 0; i < kFootprints; ++i) {
      const double u = soil_input[i] / kSoilStiffness;
      motion[kVelocity + i] = (u - motion[kDisplacement + i]) / h;
      motion[kDisplacement + i] = u;
    }
    soil_time = t + h;
    return RUMBLE_OK;
  }

  rumble_cosim_host host() {
    rumble_cosim_host h{};
    h.struct_size = sizeof(rumble_cosim_host);
    h.ctx = this;
    set_functions_1_0(h);
    set_functions_1_1(h);
    set_functions_1_4(h);
    return h;
  }

  /// The host's functions of ABI 1.0: the participants' sizes, outputs, inputs, steps and
  /// checkpoints.
  static void set_functions_1_0(rumble_cosim_host& h) {
    h.interface_size = [](void*) -> std::uint64_t { return kFootprints; };
    h.output_size = [](void*, std::uint32_t p) -> std::uint64_t {
      return p == kTrack ? kFootprints : 2 * kFootprints;
    };
    h.get_output = [](void* ctx, std::uint32_t p, double* y, std::uint64_t n) {
      const std::vector<double>& out = p == kTrack ? of(ctx).force : of(ctx).motion;
      if (n != out.size()) return RUMBLE_ERROR;
      std::memcpy(y, out.data(), n * sizeof(double));
      return RUMBLE_OK;
    };
    h.set_input = [](void* ctx, std::uint32_t p, const rumble_waveform* w) {
      std::vector<double>& in = p == kTrack ? of(ctx).track_input : of(ctx).soil_input;
      check(w->order == 0, "inputs are held constant (order 0)");
      if (w->order != 0 || w->n != in.size()) return RUMBLE_ERROR;
      std::memcpy(in.data(), w->coeff, in.size() * sizeof(double));
      return RUMBLE_OK;
    };
    h.advance = [](void* ctx, std::uint32_t p, double t, double step) {
      return p == kTrack ? of(ctx).advance_track(t, step) : of(ctx).advance_soil(t, step);
    };
    // Either participant may be put back, when it can; slots 0 .. RUMBLE_CHECKPOINT_SLOTS-1.
    h.save = [](void* ctx, std::uint32_t p, std::uint32_t slot) {
      StandIn& s = of(ctx);
      const bool can = s.can_save(p, slot);
      check(can, "save of a participant that can checkpoint, in a valid slot");
      if (!can) return RUMBLE_ERROR;
      ++s.saves;
      s.held[p == kTrack ? 0 : 1][slot] = true;
      if (p == kTrack) {
        s.saved_time[slot] = s.track_time;
        s.saved_force[slot] = s.force;
      } else {
        s.saved_soil_time[slot] = s.soil_time;
        s.saved_motion[slot] = s.motion;
      }
      return RUMBLE_OK;
    };
    h.restore = [](void* ctx, std::uint32_t p, std::uint32_t slot) {
      StandIn& s = of(ctx);
      const bool saved = s.can_save(p, slot) && s.held[p == kTrack ? 0 : 1][slot];
      check(saved, "restore of a saved slot");
      if (!saved) return RUMBLE_ERROR;
      s.calls += p == kTrack ? 'R' : 'Q';
      if (p == kTrack) {
        s.track_time = s.saved_time[slot];
        s.force = s.saved_force[slot];
      } else {
        s.soil_time = s.saved_soil_time[slot];
        s.motion = s.saved_motion[slot];
      }
      return RUMBLE_OK;
    };
    h.step_done = [](void*, double, double, double) {
      check(false, "a 1.1 coupler reports with step_report, not step_done");
      return RUMBLE_ERROR;
    };
    h.log = [](void*, std::int32_t, const char*) {};
  }

  /// The host's functions ABI 1.1 added: names, channel groups, step reports, checkpoint care.
  static void set_functions_1_1(rumble_cosim_host& h) {
    h.participant_count = [](void*) -> std::uint32_t { return 2; };
    h.participant_name = [](void*, std::uint32_t p) -> const char* {
      return p == kTrack ? "track" : p == kSoil ? "soil" : nullptr;
    };
    h.channel_groups = [](void*, std::uint32_t p, std::uint32_t side, rumble_channel_group* out,
                          std::uint64_t capacity, std::uint64_t* n) {
      const bool output = side == RUMBLE_SIDE_OUTPUT;
      if (p == kTrack) {
        return output ? groups(kTrackOutputs, 1, out, capacity, n)
                      : groups(kTrackInputs, 2, out, capacity, n);
      }
      return output ? groups(kSoilOutputs, 2, out, capacity, n)
                    : groups(kSoilInputs, 1, out, capacity, n);
    };
    h.step_report = [](void* ctx, const rumble_step_report* r) {
      Report k;
      k.t = r->t;
      k.H = r->H;
      k.iterations = r->iterations;
      k.converged = r->converged != 0;
      k.participants = r->participants;
      for (std::uint32_t g = 0; g < r->n_residuals; ++g) {
        k.groups.emplace_back(r->residuals[g].group);
        k.absolute.push_back(r->residuals[g].absolute);
        k.relative.push_back(r->residuals[g].relative);
      }
      of(ctx).reports.push_back(k);
      return RUMBLE_OK;
    };
    h.free_checkpoint = [](void* ctx, std::uint32_t p, std::uint32_t slot) {
      StandIn& s = of(ctx);
      check(s.can_save(p, slot), "a free of a participant that can checkpoint, in a valid slot");
      if (s.can_save(p, slot)) s.held[p == kTrack ? 0 : 1][slot] = false;
      ++s.frees;
      return RUMBLE_OK;
    };
    h.can_checkpoint = [](void* ctx, std::uint32_t p) -> std::int32_t {
      return of(ctx).can_save(p, 0) ? 1 : 0;
    };
  }

  /// The host's function ABI 1.4 added: the footprint layout (CosimHost::footprints()), for a
  /// scheme that applies loads of its own: 2.6 x 0.26 m sleepers 0.6 m apart.
  static void set_functions_1_4(rumble_cosim_host& h) {
    h.footprint_layout = [](void*, rumble_footprint* out, std::uint64_t capacity,
                            std::uint64_t* n) {
      *n = kFootprints;
      for (std::uint64_t i = 0; i < kFootprints && i < capacity; ++i)
        out[i] = {0.6 * static_cast<double>(i), 0.0, 2.6, 0.26};
      return RUMBLE_OK;
    };
  }
};

/// Runs the coupler over [kStart, kEnd] against `standin`; returns its status and message.
rumble_status run(const rumble_factory& f, StandIn& standin, std::string& message) {
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  host.abi_minor = RUMBLE_ABI_MINOR;
  rumble_instance* self = nullptr;
  const char* error = nullptr;
  if (f.create("{}", &host, &self, &error) != RUMBLE_OK) {
    message = std::string("create: ") + (error != nullptr ? error : "");
    return RUMBLE_ERROR;
  }
  const auto& api = *static_cast<const rumble_coupler_api*>(f.api);
  const rumble_cosim_host cosim = standin.host();
  const rumble_status status = api.run(self, &cosim, kStart, kEnd, kStep);
  message = api.common.last_message(self);
  api.common.destroy(self);
  return status;
}

/// A stand-in whose soil starts displaced (u_0), at rest.
StandIn displaced() {
  StandIn s;
  s.motion[kDisplacement + 0] = 2.0e-3;
  s.motion[kDisplacement + 1] = 1.0e-3;
  return s;
}

/// u after `steps` final steps from u_0, per footprint.
void check_answer(const StandIn& s, std::size_t steps, const std::string& what) {
  const double r = -kTrackStiffness / kSoilStiffness;
  const StandIn start = displaced();
  for (std::size_t i = 0; i < kFootprints; ++i) {
    const double u_star = kLoad[i] / (kSoilStiffness + kTrackStiffness);
    const double u0 = start.motion[kDisplacement + i];
    const double expected = u_star + (u0 - u_star) * std::pow(r, static_cast<double>(steps));
    check_close(
        s.motion[kDisplacement + i], expected, 1e-12,
        what + ": u after " + std::to_string(steps) + " steps, footprint " + std::to_string(i));
  }
}

/// The groups' residuals of a report, by name (-1 when absent).
double residual(const Report& r, const std::string& group, bool relative) {
  for (std::size_t g = 0; g < r.groups.size(); ++g)
    if (r.groups[g] == group) return relative ? r.relative[g] : r.absolute[g];
  check(false, "no residual of group '" + group + "' reported");
  return -1.0;
}

// ---- The contract every coupler keeps with the host, whatever its scheme.

/// The run ends at kEnd on both sides, reports each final step once with no gap or overlap from
/// kStart to kEnd, and gives back every checkpoint it took.
void check_contract(const StandIn& s, const std::string& what) {
  check(std::abs(s.track_time - kEnd) < 1e-12 && std::abs(s.soil_time - kEnd) < 1e-12,
        what + ": both participants end at the run's end");
  double t = kStart;
  for (const Report& r : s.reports) {
    check(std::abs(r.t - t) < 1e-12 && r.H > 0.0, what + ": the reported steps follow each other");
    t = r.t + r.H;
  }
  check(!s.reports.empty() && std::abs(t - kEnd) < 1e-12, what + ": the reports reach the end");
  check(!s.holds_a_checkpoint(), what + ": every checkpoint is freed");
}

void keeps_the_contract(const rumble_factory& f) {
  std::string message;
  StandIn plain = displaced();
  check(run(f, plain, message) == RUMBLE_OK, "run: " + message);
  check_contract(plain, "a plain run");
  // A refusal (DISCARD) is retried shorter after the participants are put back, or stops the
  // run with a message saying who refused where; it never ends a run as if it were complete.
  for (const bool soil : {true, false}) {
    StandIn refusing = displaced();
    (soil ? refusing.soil_max_step : refusing.track_max_step) = 0.6e-3;
    const std::string who = soil ? "the soil" : "the track";
    if (run(f, refusing, message) == RUMBLE_OK) {
      check_contract(refusing, "a run where " + who + " refuses long steps");
      for (const Report& r : refusing.reports)
        check(r.H <= 0.6e-3 + 1e-12, "no step longer than " + who + " accepts is reported");
    } else {
      check(message.find("refused") != std::string::npos,
            "a run stopped by a refusal says so: " + message);
    }
  }
}

// ---- This template's scheme: Gauss-Seidel of order 0 (track first). Replace these checks
// with your scheme's answers when you change the scheme.

void closed_form(const rumble_factory& f) {
  StandIn s = displaced();
  std::string message;
  check(run(f, s, message) == RUMBLE_OK, "run: " + message);
  const std::size_t steps = 11;
  std::string expected_calls;
  for (std::size_t k = 0; k < steps; ++k) expected_calls += "TS";
  check(s.calls == expected_calls, "track then soil in every step: " + s.calls);
  check(s.saves == 11 && s.frees == 1, "the track saved at each step's start, freed at the end");
  check(s.reports.size() == steps, std::to_string(s.reports.size()) + " steps reported, not 11");
  for (std::size_t k = 0; k < s.reports.size(); ++k) {
    const Report& r = s.reports[k];
    check_close(r.t, kStart + static_cast<double>(k) * kStep, 1e-15, "step start");
    check_close(r.H, k + 1 < steps ? kStep : kEnd - 10 * kStep, 1e-9, "step length");
    check(r.iterations == 1 && r.converged && r.participants == 0,
          "explicit: 1 iteration, converged, final for every participant");
    check(r.groups.size() == 2, "one residual per soil output group");
  }
  check_answer(s, steps, "closed form");

  // Residuals of steps 1 and 2: |what the track used - what the soil produced| per group, over
  // the group's largest |value| in the run so far (u_0 for displacement, as u decays to u*).
  if (s.reports.size() < 2) return;
  const StandIn start = displaced();
  double u[3][kFootprints], v[3][kFootprints];
  for (std::size_t i = 0; i < kFootprints; ++i) {
    u[0][i] = start.motion[kDisplacement + i];
    v[0][i] = 0.0;
    for (std::size_t k = 1; k < 3; ++k) {
      u[k][i] = (kLoad[i] - kTrackStiffness * u[k - 1][i]) / kSoilStiffness;
      v[k][i] = (u[k][i] - u[k - 1][i]) / kStep;
    }
  }
  double u_scale = 0.0, v_scale = 0.0;
  for (std::size_t k = 1; k < 3; ++k) {
    double du = 0.0, dv = 0.0;
    for (std::size_t i = 0; i < kFootprints; ++i) {
      du = std::max(du, std::abs(u[k][i] - u[k - 1][i]));
      dv = std::max(dv, std::abs(v[k][i] - v[k - 1][i]));
      u_scale = std::max({u_scale, std::abs(u[k - 1][i]), std::abs(u[k][i])});
      v_scale = std::max({v_scale, std::abs(v[k - 1][i]), std::abs(v[k][i])});
    }
    const Report& r = s.reports[k - 1];
    const std::string step = "step " + std::to_string(k) + " residual of ";
    check_close(residual(r, "footprint_displacement", false), du, 1e-12, step + "displacement [m]");
    check_close(residual(r, "footprint_displacement", true), du / u_scale, 1e-12,
                step + "displacement, relative to the run's scale");
    check_close(residual(r, "footprint_velocity", false), dv, 1e-12, step + "velocity [m/s]");
    check_close(residual(r, "footprint_velocity", true), dv / v_scale, 1e-12,
                step + "velocity, relative to the run's scale");
  }
}

// A soil that refuses steps over 0.6 ms: each 1 ms step is refused once, the track is put back
// and the step is taken as two halves; the last step (0.5 ms) is taken as it is. 21 final steps.
void soil_discard_is_taken_as_halves(const rumble_factory& f) {
  StandIn s = displaced();
  s.soil_max_step = 0.6e-3;
  std::string message;
  check(run(f, s, message) == RUMBLE_OK, "halved run: " + message);
  std::string expected_calls;
  for (int k = 0; k < 10; ++k) expected_calls += "TsRTSTS";
  expected_calls += "TS";
  check(s.calls == expected_calls, "refused, track restored, halves: " + s.calls);
  check(s.reports.size() == 21, std::to_string(s.reports.size()) + " steps reported, not 21");
  for (std::size_t k = 0; k < s.reports.size(); ++k) {
    check_close(s.reports[k].t, static_cast<double>(k) * 0.5e-3, 1e-12, "halved step start");
    check_close(s.reports[k].H, 0.5e-3, 1e-12, "halved step length");
  }
  check_answer(s, 21, "halved");
}

// A track that refuses steps over 0.6 ms: nothing to restore (the soil has not moved).
void track_discard_is_taken_as_halves(const rumble_factory& f) {
  StandIn s = displaced();
  s.track_max_step = 0.6e-3;
  std::string message;
  check(run(f, s, message) == RUMBLE_OK, "halved run: " + message);
  std::string expected_calls;
  for (int k = 0; k < 10; ++k) expected_calls += "tTSTS";
  expected_calls += "TS";
  check(s.calls == expected_calls, "refused by the track, halves: " + s.calls);
  check_answer(s, 21, "halved for the track");
}

// A refusal that halving cannot cure, or that needs a checkpoint the track does not offer,
// stops the run with who, where, why and the fix.
void discard_that_cannot_be_retried_stops_the_run(const rumble_factory& f) {
  StandIn s = displaced();
  s.soil_max_step = 1.0e-7;  // 1 ms / 2^10 = 0.98 us is still refused
  std::string message;
  check(run(f, s, message) == RUMBLE_ERROR, "a soil refusing every step makes the run fail");
  check(message ==
            "participant 'soil' refused the step starting at t = 0.000000 s of 0.000001 s "
            "(DISCARD) and it cannot be retried: halved 10 times already; reduce "
            "time.macro_step or raise the participant's own step limit",
        "message: " + message);

  StandIn n = displaced();
  n.soil_max_step = 0.6e-3;
  n.track_checkpoints = false;
  check(run(f, n, message) == RUMBLE_ERROR, "a soil DISCARD without a track checkpoint fails");
  check(message ==
            "participant 'soil' refused the step starting at t = 0.000000 s of 0.001000 s "
            "(DISCARD) and it cannot be retried: the track advanced first and cannot be "
            "restored (it offers no checkpoint); reduce time.macro_step or raise the "
            "participant's own step limit",
        "message: " + message);
  check(n.saves == 0, "no save asked of a track that cannot checkpoint");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <path of %s.so>\n", argv[0], kType);
    return 2;
  }
  const rumble_factory* f = load_factory(argv[1], RUMBLE_KIND_COUPLER, kType);
  if (f == nullptr) return 1;
  keeps_the_contract(*f);  // every coupler
  closed_form(*f);         // this template's scheme, from here on
  soil_discard_is_taken_as_halves(*f);
  track_discard_is_taken_as_halves(*f);
  discard_that_cannot_be_retried_stops_the_run(*f);
  if (failures == 0) std::printf("%s: all checks passed\n", kType);
  return failures == 0 ? 0 : 1;
}
