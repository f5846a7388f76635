// template_coupler_test: the built template_coupler library, loaded the way the engine loads it
// (dlopen, the one exported entry point, the C function table), run against a stand-in host
// whose two participants are linear and static, so that the coupled answer of Gauss-Seidel
// order 0 is known in closed form:
//   track: F = a - b u   (u: the footprint displacement it was given, held over the step)
//   soil:  u = F / s     (F: the footprint force it was given, held over the step)
// Per macro step u_{k+1} = (a - b u_k) / s, so u_k = u* + (u_0 - u*) r^k with u* = a / (s + b)
// and r = -b / s. Standard C++17 and the SDK headers only: no test framework, no engine.
// `ctest` runs it with the library's path as the argument; it prints each failed check and exits
// non-zero when there is one.
#include <dlfcn.h>
#include <rumble/abi.h>

#include <algorithm>
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

/// The host side of a run: the two stand-in participants and a record of the coupler's calls.
struct StandIn {
  std::vector<double> force = std::vector<double>(kFootprints, 0.0);       // track output
  std::vector<double> motion = std::vector<double>(2 * kFootprints, 0.0);  // soil output: u, v
  std::vector<double> track_input = motion, soil_input = force;
  std::string calls;  // 'T' / 'S' per advance of track / soil
  std::vector<double> step_t, step_h, residual;
  int discard_soil_at_step = -1;

  static StandIn& of(void* ctx) { return *static_cast<StandIn*>(ctx); }

  rumble_cosim_host host() {
    rumble_cosim_host h{};
    h.struct_size = sizeof(rumble_cosim_host);
    h.ctx = this;
    h.interface_size = [](void*) -> std::uint64_t { return kFootprints; };
    h.output_size = [](void*, std::uint32_t p) -> std::uint64_t {
      return p == RUMBLE_PARTICIPANT_TRACK ? kFootprints : 2 * kFootprints;
    };
    h.get_output = [](void* ctx, std::uint32_t p, double* y, std::uint64_t n) {
      const std::vector<double>& out =
          p == RUMBLE_PARTICIPANT_TRACK ? of(ctx).force : of(ctx).motion;
      if (n != out.size()) return RUMBLE_ERROR;
      std::memcpy(y, out.data(), n * sizeof(double));
      return RUMBLE_OK;
    };
    h.set_input = [](void* ctx, std::uint32_t p, const rumble_waveform* w) {
      std::vector<double>& in =
          p == RUMBLE_PARTICIPANT_TRACK ? of(ctx).track_input : of(ctx).soil_input;
      check(w->order == 0, "inputs are held constant (order 0)");
      if (w->order != 0 || w->n != in.size()) return RUMBLE_ERROR;
      std::memcpy(in.data(), w->coeff, in.size() * sizeof(double));
      return RUMBLE_OK;
    };
    h.advance = [](void* ctx, std::uint32_t p, double, double) {
      StandIn& s = of(ctx);
      s.calls += p == RUMBLE_PARTICIPANT_TRACK ? 'T' : 'S';
      if (p == RUMBLE_PARTICIPANT_TRACK) {
        for (std::size_t i = 0; i < kFootprints; ++i)
          s.force[i] = kLoad[i] - kTrackStiffness * s.track_input[i];
      } else {
        if (static_cast<int>(s.step_t.size()) == s.discard_soil_at_step) return RUMBLE_DISCARD;
        for (std::size_t i = 0; i < kFootprints; ++i)
          s.motion[i] = s.soil_input[i] / kSoilStiffness;
      }
      return RUMBLE_OK;
    };
    // Gauss-Seidel repeats no step: a checkpoint call is a failure.
    h.save = [](void*, std::uint32_t, std::uint32_t) { return RUMBLE_ERROR; };
    h.restore = [](void*, std::uint32_t, std::uint32_t) { return RUMBLE_ERROR; };
    h.step_done = [](void* ctx, double t, double step, double interface_residual) {
      of(ctx).step_t.push_back(t);
      of(ctx).step_h.push_back(step);
      of(ctx).residual.push_back(interface_residual);
      return RUMBLE_OK;
    };
    h.log = [](void*, std::int32_t, const char*) {};
    return h;
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

void closed_form(const rumble_factory& f) {
  StandIn s;
  s.motion = {2.0e-3, 1.0e-3, 0.0, 0.0};  // u_0, then v
  const std::vector<double> u0 = s.motion;
  std::string message;
  check(run(f, s, message) == RUMBLE_OK, "run: " + message);
  const std::size_t steps = 11;
  std::string expected_calls;
  for (std::size_t k = 0; k < steps; ++k) expected_calls += "TS";
  check(s.calls == expected_calls, "track then soil in every step: " + s.calls);
  check(s.step_t.size() == steps, std::to_string(s.step_t.size()) + " steps done, not 11");
  for (std::size_t k = 0; k < s.step_t.size(); ++k) {
    check_close(s.step_t[k], kStart + static_cast<double>(k) * kStep, 1e-15, "step start");
    check_close(s.step_h[k], k + 1 < steps ? kStep : kEnd - 10 * kStep, 1e-9, "step length");
  }
  const double r = -kTrackStiffness / kSoilStiffness;
  for (std::size_t i = 0; i < kFootprints; ++i) {
    const double u_star = kLoad[i] / (kSoilStiffness + kTrackStiffness);
    const double expected = u_star + (u0[i] - u_star) * std::pow(r, static_cast<double>(steps));
    check_close(s.motion[i], expected, 1e-12, "u after 11 steps, footprint " + std::to_string(i));
  }
  // Step 1's residual: the displacements changed from u_0 to u_1 = (a - b u_0) / s.
  double change = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < kFootprints; ++i) {
    const double u1 = (kLoad[i] - kTrackStiffness * u0[i]) / kSoilStiffness;
    change = std::max(change, std::abs(u1 - u0[i]));
    scale = std::max(scale, std::abs(u1));
  }
  check(!s.residual.empty(), "residuals reported");
  if (!s.residual.empty()) check_close(s.residual[0], change / scale, 1e-12, "residual of step 1");
}

// A refused step stops the run with what, where (participant, time) and the fix.
void discard_stops_the_run(const rumble_factory& f) {
  StandIn s;
  s.discard_soil_at_step = 2;
  std::string message;
  check(run(f, s, message) == RUMBLE_ERROR, "a soil DISCARD makes the run fail");
  check(message ==
            "template_coupler: the soil refused the macro step at t = 0.002000 s; this "
            "coupler cannot retry: use a smaller time.macro_step",
        "message: " + message);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <path of %s.so>\n", argv[0], kType);
    return 2;
  }
  const rumble_factory* f = load_factory(argv[1], RUMBLE_KIND_COUPLER, kType);
  if (f == nullptr) return 1;
  closed_form(*f);
  discard_stops_the_run(*f);
  if (failures == 0) std::printf("%s: all checks passed\n", kType);
  return failures == 0 ? 0 : 1;
}
