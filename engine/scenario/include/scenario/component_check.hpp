// What validation can only learn from the components themselves: it builds them as a run would
// (every vehicle, the soil and the coupler's extra soils, the coupler), lets the soils accept the
// track's footprint layout, and asks the soils for their slowest wave speeds (ABI 1.1). A
// refusal becomes an error at the component's pointer, a vehicle faster than the slowest
// Rayleigh speed a warning (critical-speed regime), so that `rumble validate` reports what
// `rumble run` would otherwise only find when it starts. Plugin code runs here: constructors
// only (no step), which the plugin guide asks to keep cheap.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble {
class BuiltSoils;
class PluginRegistry;
}  // namespace rumble

namespace rumble::scenario {

/// scenario: valid against the engine's and the plugins' schemas, defaults filled, relations
/// checked. The soils that accept the layout go to `keep` when given (for the run that follows).
std::vector<Diagnostic> check_components(const nlohmann::json& scenario,
                                         const std::filesystem::path& scenario_dir,
                                         const PluginRegistry& registry,
                                         BuiltSoils* keep = nullptr);

}  // namespace rumble::scenario
