#include "scenario/component_check.hpp"

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "plugin/built_soils.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "track/footprint_layout.hpp"
#include "track/track_config.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

std::string one_decimal(double x) {
  std::ostringstream s;
  s << std::round(x * 10.0) / 10.0;
  return s.str();
}

/// Builds the component at pointer with make(type, params); a refusal is a finding there.
template <class Make>
bool build(const json& component, const std::string& pointer, rumble_kind kind,
           const PluginRegistry& registry, std::vector<Diagnostic>& out, Make&& make) {
  const ComponentType* type = registry.find(kind, component.at("type").get<std::string>());
  if (type == nullptr) return false;  // validate has reported it
  try {
    make(*type, component.value("params", json::object()));
    return true;
  } catch (const std::exception& e) {
    out.push_back(finding(pointer + "/params", e.what()));
    return false;
  }
}

/// The soil at pointer accepts the layout; returns its slowest Rayleigh speed [m/s] (0: unknown).
/// A soil that accepted it goes to `keep` when given.
double check_soil(const json& component, const std::string& pointer,
                  const std::filesystem::path& dir, const std::vector<rumble_footprint>& layout,
                  const PluginRegistry& registry, std::vector<Diagnostic>& out, BuiltSoils* keep) {
  double c_r = 0.0;
  build(component, pointer, RUMBLE_KIND_SOIL, registry, out,
        [&](const ComponentType& type, const json& params) {
          auto soil = std::make_unique<SoilInstance>(type, pointer, params, dir);
          double c_s = 0.0;
          if (!soil->wave_speeds(c_s, c_r)) c_r = 0.0;
          try {
            soil->accept_layout(layout);
          } catch (const std::exception& e) {
            out.push_back(finding(pointer, e.what()));
            return;
          }
          if (keep != nullptr) keep->keep(pointer, type.type_name, params, layout, std::move(soil));
        });
  return c_r;
}

}  // namespace

std::vector<Diagnostic> check_components(const json& scenario,
                                         const std::filesystem::path& scenario_dir,
                                         const PluginRegistry& registry, BuiltSoils* keep) {
  std::vector<Diagnostic> out;
  const json& vehicles = scenario.at("vehicles");
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    build(vehicles[i], "/vehicles/" + std::to_string(i), RUMBLE_KIND_VEHICLE, registry, out,
          [&](const ComponentType& type, const json& params) {
            VehicleInstance(type, "/vehicles/" + std::to_string(i), params, scenario_dir);
          });
  }
  const std::vector<rumble_footprint> layout =
      footprint_layout(TrackConfig::from_json(scenario.at("track")));
  const double c_r =
      check_soil(scenario.at("soil"), "/soil", scenario_dir, layout, registry, out, keep);
  const json& coupling = scenario.at("coupling");
  const json extras = coupling.value("participants", json::object());
  for (const auto& [name, component] : extras.items())
    check_soil(component, "/coupling/participants/" + name, scenario_dir, layout, registry, out,
               keep);
  build(coupling, "/coupling", RUMBLE_KIND_COUPLER, registry, out,
        [&](const ComponentType& type, const json& params) {
          CouplerInstance(type, "/coupling", params, scenario_dir);
        });

  // Critical-speed regime: the reduced soils do not represent the Mach cone that forms above
  // the Rayleigh wave speed of the softest layer.
  if (c_r <= 0.0) return out;
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const double speed = vehicles[i].at("speed").get<double>();
    if (speed <= c_r) continue;
    std::ostringstream m;
    m << "the speed " << speed << " m/s is above the soil's Rayleigh wave speed "
      << one_decimal(c_r) << " m/s (critical-speed regime)";
    out.push_back(finding("/vehicles/" + std::to_string(i) + "/speed", m.str(),
                          "results then depend on the soil model capturing the Mach cone; check "
                          "with a full 3D soil, or lower the speed",
                          Diagnostic::Severity::kWarning));
  }
  return out;
}

}  // namespace rumble::scenario
