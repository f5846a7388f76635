// The FEM soil's settings in the tests and benchmarks, built as the plugin builds them: params
// validated against the soil's schema by the engine's SchemaChecker (as the host does), then
// read by read_settings, which reads every default the params leave out from the schema itself.
// So a test states only what it changes, and the defaults stay the schema's alone
// (fem_schema.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include "fem_settings.hpp"

namespace rumble::test {

/// read_settings of `params` after validation (std::invalid_argument naming every schema
/// refusal).
fem::FemSettings settings_from(const nlohmann::json& params);

/// settings_from a half-space of E [Pa], nu [-] and rho [kg/m^3], with `more` merged over it
/// (JSON merge patch: {"mesh": {"radius": 8}} keeps the other mesh keys).
fem::FemSettings soil_settings(double E, double nu, double rho,
                               const nlohmann::json& more = nlohmann::json::object());

}  // namespace rumble::test
