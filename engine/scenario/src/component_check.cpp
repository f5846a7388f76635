#include "scenario/component_check.hpp"

#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>

#include "plugin/built_soils.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "scenario/run_spec.hpp"
#include "track_spec/footprint_layout.hpp"
#include "track_spec/track_config.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

std::string one_decimal(double x) {
  std::ostringstream s;
  s << std::round(x * 10.0) / 10.0;
  return s.str();
}

/// Where a plugin's refusal points. Plugins begin a refusal of one of their keys with
/// "<plugin>: params/<key>:" (docs/plugin-guide.md §6: "fem: params/mesh/radius: ..."): the
/// finding goes to that key under `component` (as far down as its params, defaults filled, have
/// it); without one, to `otherwise`. A key named elsewhere in the text is not the one blamed.
std::string refused_pointer(const std::string& component, const json& params,
                            const std::string& message, const std::string& otherwise) {
  constexpr std::string_view kKey = ": params/";
  const std::size_t at = message.find(kKey);
  if (at == std::string::npos) return otherwise;
  std::string pointer = component + "/params";
  const json* node = &params;
  std::size_t begin = at + kKey.size();
  for (;;) {
    std::size_t end = begin;
    while (end < message.size() &&
           (std::isalnum(static_cast<unsigned char>(message[end])) != 0 || message[end] == '_'))
      ++end;
    const std::string key = message.substr(begin, end - begin);
    if (key.empty() || !node->is_object() || !node->contains(key)) break;
    pointer += "/" + key;
    node = &node->at(key);
    if (end >= message.size() || message[end] != '/') break;
    begin = end + 1;
  }
  return pointer;
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
    const json params = component.value("params", json::object());
    out.push_back(
        finding(refused_pointer(pointer, params, e.what(), pointer + "/params"), e.what()));
    return false;
  }
}

/// The receivers of /outputs/receivers that the soil cannot record (a FEM soil's point outside
/// its mesh, or in its matched layer): a finding at each, found while the soil is built rather
/// than at the run's first call, which named neither the receiver's pointer nor its index. All
/// at once first; when refused, one at a time to tell which.
void check_receivers(SoilInstance& soil, const json& scenario, std::vector<Diagnostic>& out) {
  const json& outputs = scenario.at("outputs");
  const std::vector<ReceiverSpec> receivers =
      scenario::receivers(outputs.value("receivers", json::array()),
                          TrackConfig::from_json(scenario.at("track")).middle_x());
  if (receivers.empty()) return;
  const auto probe = [](const ReceiverSpec& r) {
    return rumble_probe{r.name.c_str(), r.x, r.y, r.depth};
  };
  std::vector<rumble_probe> all;
  for (const ReceiverSpec& r : receivers) all.push_back(probe(r));
  const double interval = outputs.at("receiver_interval").get<double>();
  std::string refusal;
  try {
    soil.set_probes(all, interval);
    return;
  } catch (const std::exception& e) {
    refusal = e.what();
  }
  const std::size_t before = out.size();
  for (std::size_t i = 0; i < receivers.size(); ++i) {
    try {
      soil.set_probes({probe(receivers[i])}, interval);
    } catch (const std::exception& e) {
      std::ostringstream m;
      m << "receiver '" << receivers[i].name << "' (x " << receivers[i].x << " m, y "
        << receivers[i].y << " m, depth " << receivers[i].depth << " m) cannot be recorded by "
        << e.what();
      out.push_back(finding("/outputs/receivers/" + std::to_string(i), m.str(),
                            "move the receiver into the soil's domain, or enlarge the domain "
                            "(a FEM soil's /soil/params/mesh/radius)"));
    }
  }
  if (out.size() == before)  // each alone is recorded, the list is not
    out.push_back(
        finding("/outputs/receivers", "the receivers together cannot be recorded by " + refusal));
}

/// The soil at pointer accepts the layout; returns its slowest Rayleigh speed [m/s] (0: unknown).
/// A soil that accepted it goes to `keep` when given.
double check_soil(const json& scenario, const json& component, const std::string& pointer,
                  const std::filesystem::path& dir, const std::vector<rumble_footprint>& layout,
                  const PluginRegistry& registry, std::vector<Diagnostic>& out, BuiltSoils* keep) {
  double c_r = 0.0;
  build(component, pointer, RUMBLE_KIND_SOIL, registry, out,
        [&](const ComponentType& type, const json& params) {
          std::unique_ptr<SoilInstance> soil;
          try {  // as the run lays it (plugin/built_soils.hpp)
            soil = lay_soil(type, pointer, params, dir, layout);
          } catch (const LayoutRefused& e) {
            // The layout is the track's (/track/sleepers) unless the soil names its own key.
            out.push_back(
                finding(refused_pointer(pointer, params, e.what(), "/track/sleepers"), e.what()));
            return;
          }
          double c_s = 0.0;
          if (!soil->wave_speeds(c_s, c_r)) c_r = 0.0;
          if (pointer == "/soil") {  // the receivers are the scenario's soil's
            const std::size_t findings = out.size();
            check_receivers(*soil, scenario, out);
            if (out.size() > findings) return;
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
      check_soil(scenario, scenario.at("soil"), "/soil", scenario_dir, layout, registry, out, keep);
  const json& coupling = scenario.at("coupling");
  const json extras = coupling.value("participants", json::object());
  for (const auto& [name, component] : extras.items())
    check_soil(scenario, component, "/coupling/participants/" + name, scenario_dir, layout,
               registry, out, keep);
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
