// Shared by the boundary tests: the fixture plugins and a scenario that runs through them.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"

namespace rumble::testing {

/// Path of a fixture plugin built by tests/boundary/CMakeLists.txt, e.g. "boundary_fixtures".
std::string fixture_plugin(const std::string& name);

/// small_scenario() with the fixture libraries loaded, the soil and the coupler replaced.
nlohmann::json fixture_scenario(const nlohmann::json& soil, const nlohmann::json& coupling);

/// Runs `rumble run` on the scenario in a fresh directory; returns the results directory.
std::filesystem::path run_in(const std::string& name, const nlohmann::json& scenario,
                             CliResult& result);

/// True when two files have the same bytes.
bool same_bytes(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace rumble::testing
