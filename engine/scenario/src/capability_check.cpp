#include "scenario/capability_check.hpp"

#include <rumble/abi.h>

#include <map>
#include <string>

#include "plugin/capabilities.hpp"
#include "plugin/registry.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

struct Used {
  std::string pointer;  // of the component object, e.g. "/soil"
  const ComponentType* type;
};

/// The component at pointer when it names a known type of that kind.
const ComponentType* known(const json& scenario, const std::string& pointer, rumble_kind kind,
                           const PluginRegistry& registry) {
  const json::json_pointer p(pointer);
  if (!scenario.contains(p)) return nullptr;
  const json& c = scenario.at(p);
  if (!c.is_object() || !c.contains("type") || !c.at("type").is_string()) return nullptr;
  return registry.find(kind, c.at("type").get<std::string>());
}

/// Soils that offer every bit of `bits`, for a hint.
std::string soils_offering(const PluginRegistry& registry, std::uint64_t bits) {
  std::string list;
  for (const ComponentType& t : registry.types()) {
    if (t.kind == RUMBLE_KIND_SOIL && t.capabilities.declared && t.capabilities.has(bits))
      list += (list.empty() ? "" : ", ") + t.type_name;
  }
  return list.empty() ? "none is loaded" : list;
}

void check_needs(const ComponentType& coupler, const std::vector<Used>& soils,
                 const PluginRegistry& registry, std::vector<Diagnostic>& out) {
  const std::uint64_t needs = coupler.capabilities.soil_needs;
  for (const Used& soil : soils) {
    const Capabilities& offers = soil.type->capabilities;
    const std::uint64_t missing = needs & ~offers.offers;
    if (missing == 0 || !offers.declared) continue;  // a 1.0 soil is checked at run time
    out.push_back(finding(soil.pointer + "/type",
                          "soil type \"" + soil.type->type_name + "\" cannot " +
                              capability_text(missing) + ", which coupler \"" + coupler.type_name +
                              "\" needs of every soil it drives",
                          "choose a soil that can (" + soils_offering(registry, missing) +
                              ") or a coupler that does not need it"));
  }
}

void check_participants(const json& scenario, const ComponentType& coupler,
                        std::vector<Diagnostic>& out) {
  const json declared = json::parse(coupler.capabilities.participants_json, nullptr, false);
  const json given = scenario.at("coupling").value("participants", json::object());
  if (!declared.is_object() || !given.is_object()) return;
  for (const auto& [name, spec] : declared.items()) {
    if (spec.is_object() && spec.value("required", false) && !given.contains(name)) {
      out.push_back(
          finding("/coupling",
                  "coupler \"" + coupler.type_name + "\" needs a participant \"" + name + "\" (" +
                      spec.value("description", std::string("a soil")) + ")",
                  "add /coupling/participants/" + name + " = {\"type\": ..., \"params\": {...}}"));
    }
  }
  for (const auto& [name, component] : given.items()) {
    if (declared.contains(name)) continue;
    std::string names;
    for (const auto& [known_name, spec] : declared.items())
      names += (names.empty() ? "" : ", ") + known_name;
    out.push_back(
        finding("/coupling/participants/" + name,
                "coupler \"" + coupler.type_name + "\" drives no participant \"" + name + "\"",
                names.empty() ? "this coupler drives only the track and /soil; remove it"
                              : "its participants are: " + names));
  }
}

void check_max_step(const json& scenario, const std::vector<Used>& used,
                    std::vector<Diagnostic>& out) {
  const double H = scenario.at("time").at("macro_step").get<double>();
  for (const Used& u : used) {
    const double limit = u.type->capabilities.max_macro_step;
    if (limit > 0.0 && H > limit) {
      out.push_back(finding("/time/macro_step",
                            "must be <= " + format_number(limit) + " s, the largest macro step " +
                                kind_name(u.type->kind) + " type \"" + u.type->type_name + "\" (" +
                                u.pointer + ") accepts, got " + format_number(H),
                            "set /time/macro_step to " + format_number(limit) + " or less"));
    }
  }
}

void check_once_per_process(const std::vector<Used>& used, std::vector<Diagnostic>& out) {
  std::map<std::string, std::string> first_use;
  for (const Used& u : used) {
    if (!u.type->capabilities.has(RUMBLE_CAP_ONCE_PER_PROCESS)) continue;
    const auto [it, fresh] = first_use.emplace(u.type->type_name, u.pointer);
    if (!fresh) {
      out.push_back(finding(u.pointer + "/type",
                            "type \"" + u.type->type_name +
                                "\" allows one instance per process and is already used at " +
                                it->second,
                            "use another type here, or run the two in separate scenarios"));
    }
  }
}

/// A monolithic coupler steps the soil inside the track, never the soil plugin itself.
void check_monolithic(const json& scenario, const ComponentType& coupler,
                      std::vector<Diagnostic>& out) {
  if (!coupler.capabilities.has(RUMBLE_CAP_MONOLITHIC)) return;
  const json& outputs = scenario.at("outputs");
  for (const char* what : {"receivers", "fields"}) {
    if (!outputs.contains(what) || (outputs[what].is_array() && outputs[what].empty())) continue;
    Diagnostic d = finding(std::string("/outputs/") + what,
                           "coupler \"" + coupler.type_name +
                               "\" integrates the soil with the track from its matrices; the soil "
                               "records no " +
                               what + " in such a run",
                           "remove /outputs/" + std::string(what) +
                               ", or compare footprint motions (they are recorded)");
    d.severity = Diagnostic::Severity::kWarning;
    out.push_back(std::move(d));
  }
}

void check_fields(const json& scenario, const Used& soil, std::vector<Diagnostic>& out) {
  const Capabilities& c = soil.type->capabilities;
  if (!scenario.at("outputs").contains("fields") || c.has(RUMBLE_CAP_FIELD_OUTPUT)) return;
  Diagnostic d = finding("/outputs/fields",
                         "soil type \"" + soil.type->type_name +
                             "\" writes no field output; no snapshots will be written",
                         "remove /outputs/fields, or use a soil that offers field output (the fem "
                         "soil)");
  d.severity = Diagnostic::Severity::kWarning;
  out.push_back(std::move(d));
}

void check_receivers(const json& scenario, const Used& soil, std::vector<Diagnostic>& out) {
  const json& receivers = scenario.at("outputs").value("receivers", json::array());
  const Capabilities& c = soil.type->capabilities;
  if (receivers.empty() || !c.declared || c.has(RUMBLE_CAP_RECEIVERS)) return;
  Diagnostic d = finding(
      "/outputs/receivers",
      "soil type \"" + soil.type->type_name + "\" offers no receivers; they will not be recorded",
      "footprint motions are still recorded; use a soil that offers receivers "
      "(the fem soil) for ground vibration away from the track");
  d.severity = Diagnostic::Severity::kWarning;
  out.push_back(std::move(d));
}

/// The error for `soil` split over `ranks` ranks where `who` needs its whole matrices, read by
/// the soil's function `reads`.
Diagnostic split_soil_refused(const Used& soil, int ranks, const std::string& pointer,
                              const std::string& who, const std::string& reads,
                              const std::string& fix) {
  return finding(pointer,
                 who + " needs the whole matrices of soil type \"" + soil.type->type_name + "\" (" +
                     soil.pointer + ", its " + reads +
                     "), which no rank holds when it is split over the " + std::to_string(ranks) +
                     " MPI ranks of this launch (each holds its part)",
                 fix);
}

}  // namespace

std::vector<Diagnostic> check_split_soil(const json& scenario, const PluginRegistry& registry,
                                         int ranks, const WholeSoilCommand& command) {
  std::vector<Diagnostic> out;
  if (ranks <= 1 || !scenario.is_object() || !scenario.contains("coupling")) return out;
  const ComponentType* soil_type = known(scenario, "/soil", RUMBLE_KIND_SOIL, registry);
  if (soil_type == nullptr || !soil_type->capabilities.has(RUMBLE_CAP_DISTRIBUTED)) return out;
  const Used soil{"/soil", soil_type};
  const ComponentType* coupler = known(scenario, "/coupling", RUMBLE_KIND_COUPLER, registry);
  if (command.name != nullptr) {
    out.push_back(split_soil_refused(soil, ranks, "/soil/type",
                                     std::string(command.name) + " (" + command.why + ")",
                                     command.reads,
                                     "run " + std::string(command.name) +
                                         " without mpirun, on one process: the soil is then "
                                         "whole"));
  } else if (coupler != nullptr && coupler->capabilities.has(RUMBLE_CAP_MONOLITHIC)) {
    out.push_back(split_soil_refused(
        soil, ranks, "/coupling/type",
        "coupler \"" + coupler->type_name + "\" (it integrates the soil inside the track)",
        "linear_matrix",
        "run it without mpirun, on one process, or choose a coupler that steps the soil on its "
        "ranks (gauss_seidel, jacobi, implicit), got \"" +
            coupler->type_name + "\""));
  }
  return out;
}

std::vector<Diagnostic> check_capabilities(const json& scenario, const PluginRegistry& registry) {
  std::vector<Diagnostic> out;
  if (!scenario.is_object() || !scenario.contains("coupling") || !scenario.contains("time") ||
      !scenario.contains("outputs"))
    return out;
  std::vector<Used> used, soils;
  if (const ComponentType* t = known(scenario, "/soil", RUMBLE_KIND_SOIL, registry))
    soils.push_back({"/soil", t});
  const json participants = scenario.at("coupling").value("participants", json::object());
  for (const auto& [name, component] : participants.items()) {
    const std::string ptr = "/coupling/participants/" + name;
    if (const ComponentType* t = known(scenario, ptr, RUMBLE_KIND_SOIL, registry))
      soils.push_back({ptr, t});
  }
  used = soils;
  const ComponentType* coupler = known(scenario, "/coupling", RUMBLE_KIND_COUPLER, registry);
  if (coupler != nullptr) {
    used.push_back({"/coupling", coupler});
    check_needs(*coupler, soils, registry, out);
    check_participants(scenario, *coupler, out);
    check_monolithic(scenario, *coupler, out);
  }
  const json vehicles = scenario.value("vehicles", json::array());
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const std::string ptr = "/vehicles/" + std::to_string(i);
    if (const ComponentType* t = known(scenario, ptr, RUMBLE_KIND_VEHICLE, registry))
      used.push_back({ptr, t});
  }
  check_max_step(scenario, used, out);
  check_once_per_process(used, out);
  if (!soils.empty() && soils.front().pointer == "/soil") {
    check_receivers(scenario, soils[0], out);
    check_fields(scenario, soils[0], out);
  }
  return out;
}

}  // namespace rumble::scenario
