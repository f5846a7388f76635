// Runs a validated scenario: builds the participants, solves the static state, hands both sides
// to the coupler plugin and records every macro step. Whatever happens, summary.json says how
// the run ended, and every row recorded before a failure stays on disk.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "plugin/registry.hpp"

namespace rumble {

struct RunOptions {
  bool progress = false;  // progress line with ETA on stderr
};

struct RunOutcome {
  std::filesystem::path results_dir;
  std::string status;   // "completed", "interrupted", "failed"
  std::string message;  // why, when not completed
  int exit_code = 0;
};

/// scenario: validated, defaults filled. scenario_path: its file (relative paths resolve there).
/// Throws ConfigError for problems found while building (exit 1); run failures are reported in
/// the outcome (exit 3) after summary.json is written.
RunOutcome run_scenario(const nlohmann::json& scenario, const std::filesystem::path& scenario_path,
                        const PluginRegistry& registry, const RunOptions& options);

/// Results directory of a scenario: outputs.directory relative to the scenario file.
std::filesystem::path results_directory(const nlohmann::json& scenario,
                                        const std::filesystem::path& scenario_path);

}  // namespace rumble
