// prescribed_load_test: the built library, loaded as the engine loads it (dlopen, the one
// exported entry point, the C function table), run against a stand-in host (the ABI 1.4
// rumble_cosim_host) with three footprints at x = 0, 1, 2 m whose static forces are 100, 200 and
// 300 N. Checked: the soil takes the static forces plus the load, in closed form, on the
// footprint nearest to `x` and nowhere else, and nothing before the load starts; the track
// advances with nothing set on it; the contract every coupler keeps (both participants end at
// the run's end, one report per final step with no gap; a refused step is taken as halves).
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace {

const char* g_library = nullptr;  // the path of prescribed_load.so (main's argument)

constexpr std::size_t kN = 3;
constexpr double kStatic[kN] = {100.0, 200.0, 300.0};  // N
constexpr double kEnd = 5e-3, kStep = 1e-3;            // s

/// What the soil was given over one step it took: t, h [s], and the waveform at tau = 0 and
/// tau = 1 per footprint [N] (empty: no input was set for the step).
struct SoilStep {
  double t = 0.0, h = 0.0;
  std::vector<double> begin, end;
};

struct StandIn {
  std::vector<double> force = std::vector<double>(kStatic, kStatic + kN);  // track outputs
  std::vector<double> motion = std::vector<double>(2 * kN, 0.0);           // soil outputs
  std::vector<double> begin, end;  // the soil's pending input at tau = 0 and 1 (empty: none)
  double track_time = 0.0, soil_time = 0.0, soil_max_step = 1.0;  // s
  int track_inputs = 0;
  std::vector<SoilStep> soil_steps;
  std::vector<std::pair<double, double>> reports;  // (t, H)

  static StandIn& of(void* ctx) { return *static_cast<StandIn*>(ctx); }

  rumble_status advance(std::uint32_t p, double t, double h) {
    double& now = p == RUMBLE_PARTICIPANT_TRACK ? track_time : soil_time;
    if (std::abs(t - now) > 1e-12) return RUMBLE_ERROR;  // a participant advances from its time
    if (p == RUMBLE_PARTICIPANT_SOIL) {
      if (h > soil_max_step) return RUMBLE_DISCARD;
      soil_steps.push_back({t, h, begin, end});
    }
    now = t + h;
    return RUMBLE_OK;
  }

  rumble_cosim_host host() {
    rumble_cosim_host h{};
    h.struct_size = sizeof h;
    h.ctx = this;
    h.interface_size = [](void*) -> std::uint64_t { return kN; };
    h.output_size = [](void*, std::uint32_t p) -> std::uint64_t {
      return p == RUMBLE_PARTICIPANT_TRACK ? kN : 2 * kN;
    };
    h.get_output = [](void* ctx, std::uint32_t p, double* y, std::uint64_t n) {
      const std::vector<double>& out =
          p == RUMBLE_PARTICIPANT_TRACK ? of(ctx).force : of(ctx).motion;
      if (n != out.size()) return RUMBLE_ERROR;
      std::memcpy(y, out.data(), out.size() * sizeof(double));
      return RUMBLE_OK;
    };
    h.set_input = [](void* ctx, std::uint32_t p, const rumble_waveform* w) {
      if (p == RUMBLE_PARTICIPANT_TRACK) {
        ++of(ctx).track_inputs;
        return RUMBLE_OK;
      }
      if (w->n != kN || w->order > 2) return RUMBLE_ERROR;
      std::vector<double>& b = of(ctx).begin;
      std::vector<double>& e = of(ctx).end;
      b.assign(w->coeff, w->coeff + kN);
      e.assign(kN, 0.0);
      for (std::uint32_t k = 0; k <= w->order; ++k)
        for (std::size_t i = 0; i < kN; ++i) e[i] += w->coeff[k * kN + i];
      return RUMBLE_OK;
    };
    h.advance = [](void* ctx, std::uint32_t p, double t, double step) {
      return of(ctx).advance(p, t, step);
    };
    h.log = [](void*, std::int32_t, const char*) {};
    h.participant_count = [](void*) -> std::uint32_t { return 2; };
    h.participant_name = [](void*, std::uint32_t p) -> const char* {
      return p == RUMBLE_PARTICIPANT_TRACK  ? "track"
             : p == RUMBLE_PARTICIPANT_SOIL ? "soil"
                                            : nullptr;
    };
    h.channel_groups = [](void*, std::uint32_t p, std::uint32_t side, rumble_channel_group* out,
                          std::uint64_t capacity, std::uint64_t* n) {
      static const rumble_channel_group kForces[] = {{"footprint_force", "N", 0, kN}};
      static const rumble_channel_group kMotion[] = {{"footprint_displacement", "m", 0, kN},
                                                     {"footprint_velocity", "m/s", kN, kN}};
      const bool forces = (p == RUMBLE_PARTICIPANT_TRACK) == (side == RUMBLE_SIDE_OUTPUT);
      *n = forces ? 1u : 2u;
      for (std::uint64_t g = 0; g < *n && g < capacity; ++g)
        out[g] = forces ? kForces[g] : kMotion[g];
      return RUMBLE_OK;
    };
    h.step_report = [](void* ctx, const rumble_step_report* r) {
      if (r->participants != 0 || r->iterations != 1) return RUMBLE_ERROR;
      of(ctx).reports.emplace_back(r->t, r->H);
      return RUMBLE_OK;
    };
    h.can_checkpoint = [](void*, std::uint32_t) -> std::int32_t { return 0; };
    h.footprint_layout = [](void*, rumble_footprint* out, std::uint64_t capacity,
                            std::uint64_t* n) {
      *n = kN;
      for (std::uint64_t i = 0; i < kN && i < capacity; ++i)
        out[i] = {static_cast<double>(i), 0.0, 0.3, 0.3};
      return RUMBLE_OK;
    };
    return h;
  }
};

/// Runs the coupler with these params over [0, kEnd] at kStep; returns its status and message.
rumble_status run(const std::string& params, StandIn& s, std::string& message) {
  void* library = dlopen(g_library, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    ADD_FAILURE() << "cannot load " << g_library << ": " << dlerror();
    return RUMBLE_ERROR;
  }
  rumble_plugin_entry_fn entry = nullptr;
  void* symbol = dlsym(library, RUMBLE_PLUGIN_ENTRY_SYMBOL);
  std::memcpy(&entry, &symbol, sizeof entry);  // object to function pointer, as dlsym needs
  const rumble_factory& f = entry()->factories[0];
  rumble_host host{};
  host.struct_size = sizeof host;
  host.abi_minor = RUMBLE_ABI_MINOR;
  rumble_instance* self = nullptr;
  const char* error = nullptr;
  if (f.create(params.c_str(), &host, &self, &error) != RUMBLE_OK) {
    message = error != nullptr ? error : "";
    return RUMBLE_ERROR;
  }
  const auto& api = *static_cast<const rumble_coupler_api*>(f.api);
  const rumble_cosim_host cosim = s.host();
  const rumble_status status = api.run(self, &cosim, 0.0, kEnd, kStep);
  message = api.common.last_message(self);
  api.common.destroy(self);
  return status;
}

/// The ramp to P over rise, from start: the closed form the coupler must follow [N].
double ramp(double t, double p, double rise, double start) {
  return t <= start ? 0.0 : p * std::min((t - start) / rise, 1.0);
}

/// Both participants end at the run's end and the reports follow each other to it.
void expect_the_contract(const StandIn& s) {
  EXPECT_NEAR(s.track_time, kEnd, 1e-12);
  EXPECT_NEAR(s.soil_time, kEnd, 1e-12);
  double t = 0.0;
  for (const auto& [start, length] : s.reports) {
    EXPECT_NEAR(start, t, 1e-12);
    t = start + length;
  }
  EXPECT_NEAR(t, kEnd, 1e-12);
  EXPECT_EQ(s.track_inputs, 0) << "the track keeps the input the host gave it";
}

TEST(PrescribedLoad, TheSoilTakesTheStaticForcesPlusTheLoadOnTheNearestFootprint) {
  StandIn s;
  std::string message;
  const double p = 1000.0, rise = 2e-3, start = 1e-3;
  ASSERT_EQ(run(R"({"load": 1000, "rise_time": 2e-3, "start": 1e-3, "x": 1.2})", s, message),
            RUMBLE_OK)
      << message;
  expect_the_contract(s);
  ASSERT_EQ(s.soil_steps.size(), 5u);
  EXPECT_TRUE(s.soil_steps[0].begin.empty()) << "before the load, the host's input (F0) stays";
  for (std::size_t k = 1; k < s.soil_steps.size(); ++k) {
    const SoilStep& step = s.soil_steps[k];
    ASSERT_EQ(step.begin.size(), kN);
    for (std::size_t i = 0; i < kN; ++i) {
      const double load_begin = i == 1 ? ramp(step.t, p, rise, start) : 0.0;
      const double load_end = i == 1 ? ramp(step.t + step.h, p, rise, start) : 0.0;
      EXPECT_NEAR(step.begin[i], kStatic[i] + load_begin, 1e-9) << "step " << k << ", " << i;
      EXPECT_NEAR(step.end[i], kStatic[i] + load_end, 1e-9) << "step " << k << ", " << i;
    }
  }
}

TEST(PrescribedLoad, APulseOnTheMiddleFootprintByDefault) {
  StandIn s;
  std::string message;
  ASSERT_EQ(run(R"({"load": -500, "shape": "pulse", "rise_time": 4e-3})", s, message), RUMBLE_OK)
      << message;
  ASSERT_EQ(s.soil_steps.size(), 5u);
  for (const SoilStep& step : s.soil_steps) {
    const double t = step.t + step.h;
    const double hann = t < 4e-3 ? std::pow(std::sin(std::acos(-1.0) * t / 4e-3), 2) : 0.0;
    EXPECT_NEAR(step.end[1], kStatic[1] - 500.0 * hann, 1e-9) << "at t = " << t;
    EXPECT_DOUBLE_EQ(step.end[0], kStatic[0]);
    EXPECT_DOUBLE_EQ(step.end[2], kStatic[2]);
  }
}

TEST(PrescribedLoad, ASoilThatRefusesLongStepsTakesThemAsHalves) {
  StandIn s;
  s.soil_max_step = 0.6e-3;
  std::string message;
  ASSERT_EQ(run(R"({"load": 1000, "rise_time": 2e-3})", s, message), RUMBLE_OK) << message;
  expect_the_contract(s);
  ASSERT_EQ(s.soil_steps.size(), 10u);
  for (const SoilStep& step : s.soil_steps) {
    EXPECT_NEAR(step.h, 0.5e-3, 1e-12);
    EXPECT_NEAR(step.end[1], kStatic[1] + ramp(step.t + step.h, 1000.0, 2e-3, 0.0), 1e-9);
  }
  StandIn never;
  never.soil_max_step = 1e-9;
  EXPECT_EQ(run("{}", never, message), RUMBLE_ERROR);
  EXPECT_NE(message.find("refused"), std::string::npos) << message;
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <path of prescribed_load.so>\n", argv[0]);
    return 2;
  }
  g_library = argv[1];
  return RUN_ALL_TESTS();
}
