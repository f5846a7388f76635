// Runs a validated scenario: builds the components (run_components), solves the static state,
// hands the participants to the coupler plugin, records every final macro step (step_observer)
// and writes summary.json (summary_writer). Whatever happens, summary.json says how the run
// ended, and every row recorded before a failure stays on disk.
#pragma once

#include <filesystem>
#include <string>

#include "plugin/built_soils.hpp"
#include "plugin/registry.hpp"
#include "results/results_directory.hpp"
#include "run/summary_writer.hpp"
#include "scenario/run_spec.hpp"

namespace rumble {

struct RunOptions {
  bool progress = false;              // progress line with ETA on stderr
  double heartbeat_seconds = 1.0;     // at most one heartbeat write in summary.json per this time
  BuiltSoils* built_soils = nullptr;  // soils the validation built, taken when they match
  bool size_confirmed = false;        // --yes: a run beyond the size limits is wanted
};

struct RunOutcome {
  std::filesystem::path results_dir;
  RunStatus status = RunStatus::kFailed;
  std::string message;  // why, when not completed
  int exit_code = 3;
};

/// Runs into `results` (spec.outputs.directory, held by the caller for as long as it writes
/// there, plots included). Throws ConfigError for problems found while building (exit 1); run
/// failures are reported in the outcome (exit 3) after summary.json is written.
RunOutcome run_scenario(const scenario::RunSpec& spec, const PluginRegistry& registry,
                        ResultsDirectory& results, const RunOptions& options);

}  // namespace rumble
