// Cost of the vehicle/track participant's micro-step (the hot loop of every run): REF-A track
// (railFE values), 100 sleepers at 0.6 m, 4 elements per bay, footprints held still, one wheel
// (750 kg, 100 kN) rolling at 30 m/s. Reports the time per micro-step and per simulated second,
// and the Newton iterations of the last micro-step of each macro step (on average).
//   build/release/bin/track_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include "plugin/registry.hpp"
#include "scenario/scenario_schema.hpp"
#include "track/track_participant.hpp"

namespace {

std::unique_ptr<rumble::TrackParticipant> make_track(int elements_per_bay) {
  static rumble::PluginRegistry registry = [] {
    rumble::PluginRegistry r;
    r.load_directory(RUMBLE_BENCH_PLUGIN_DIR);
    return r;
  }();
  const nlohmann::json track = {{"sleepers",
                                 {{"count", 100},
                                  {"spacing", 0.6},
                                  {"mass", 177.5},
                                  {"footprint", {{"length", 2.6}, {"width", 0.26}}}}},
                                {"rail",
                                 {{"E", 2.1e11},
                                  {"I", 3.055e-5},
                                  {"mass_per_length", 60.34},
                                  {"elements_per_bay", elements_per_bay}}},
                                {"railpad", {{"k", 2e8}, {"c", 2.8e4}}},
                                {"ballast", {{"k", 4e7}, {"c", 4.7e4}}}};
  rumble::VehicleSet vehicles;
  vehicles.add(std::make_unique<rumble::VehicleInstance>(
                   *registry.find(RUMBLE_KIND_VEHICLE, "single_wheel"), "/vehicles/0",
                   nlohmann::json{{"mass", 750.0}, {"static_load", 1e5 - 750.0 * 9.81}}, "."),
               "wheel", 30.0, 10.0);
  auto t = std::make_unique<rumble::TrackParticipant>(
      rumble::TrackConfig::from_json(rumble::scenario::track_with_defaults(track)),
      std::move(vehicles));
  t->solve_static({});
  return t;
}

void BM_TrackMacroStep(benchmark::State& state) {
  auto track = make_track(static_cast<int>(state.range(0)));
  const double H = 1e-3;  // s
  const double h = H / std::ceil(H / track->micro_step_limit() - 1e-9);
  double t = 0.0, newton_iterations = 0.0;
  for (auto _ : state) {
    track->advance(t, H);
    newton_iterations += track->newton_iterations_last_step();
    t += H;
    if (t > 1.0) {  // stay on the track: restart from the static state
      state.PauseTiming();
      track = make_track(static_cast<int>(state.range(0)));
      t = 0.0;
      state.ResumeTiming();
    }
  }
  const double micro_steps = static_cast<double>(state.iterations()) * H / h;
  state.counters["micro_step_us"] = h * 1e6;
  state.counters["dofs"] = static_cast<double>(track->track_x().size());
  // Newton iterations of the last micro-step of each macro step, on average.
  state.counters["newton_its"] = newton_iterations / static_cast<double>(state.iterations());
  state.counters["per_micro_step"] =
      benchmark::Counter(micro_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["wall_per_simulated_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * H,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TrackMacroStep)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
