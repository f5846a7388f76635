#include "track_fixture.hpp"

#include "scenario/scenario_schema.hpp"

namespace rumble::testing {

nlohmann::json ref_a_track(int sleepers, int elements_per_bay) {
  return {{"sleepers",
           {{"count", sleepers},
            {"spacing", 0.6},
            {"mass", 177.5},
            {"footprint", {{"length", 2.6}, {"width", 0.26}}}}},
          {"rail",
           {{"E", 2.1e11},
            {"I", 3.055e-5},
            {"mass_per_length", 60.34},
            {"elements_per_bay", elements_per_bay},
            {"overhang_bays", 1}}},
          {"railpad", {{"k", 2.0e8}, {"c", 2.8e4}}},
          {"ballast", {{"k", 4.0e7}, {"c", 4.7e4}}}};
}

const PluginRegistry& plugins() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.load_directory(RUMBLE_TEST_PLUGIN_DIR);
    return r;
  }();
  return registry;
}

std::unique_ptr<TrackParticipant> make_track(const nlohmann::json& track,
                                             const nlohmann::json& vehicles) {
  VehicleSet set;
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const auto& v = vehicles[i];
    const ComponentType* type =
        plugins().find(RUMBLE_KIND_VEHICLE, v.at("type").get<std::string>());
    if (type == nullptr) throw std::runtime_error("vehicle plugin not built: " + v.dump());
    set.add(std::make_unique<VehicleInstance>(*type, "/vehicles/" + std::to_string(i),
                                              v.at("params"), RUMBLE_TEST_SOURCE_DIR),
            "vehicle" + std::to_string(i), v.at("speed").get<double>(),
            v.at("start").get<double>());
  }
  return std::make_unique<TrackParticipant>(
      TrackConfig::from_json(scenario::track_with_defaults(track)), std::move(set));
}

nlohmann::json single_wheel(double mass, double load, double speed, double start) {
  return {{"type", "single_wheel"},
          {"params", {{"mass", mass}, {"static_load", load - mass * 9.81}}},
          {"speed", speed},
          {"start", start}};
}

}  // namespace rumble::testing
