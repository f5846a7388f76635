// Checks the engine makes after schema validation, on relations between values that a JSON
// Schema cannot express: time steps, vehicles staying on the track, unevenness bands. Each
// finding names its JSON pointer; positions are added by the caller. (What needs the components
// themselves, such as the soil's wave speeds, is in component_check.hpp.)
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble {

/// scenario: schema-valid, defaults filled.
std::vector<scenario::Diagnostic> check_scenario_relations(const nlohmann::json& scenario);

}  // namespace rumble
