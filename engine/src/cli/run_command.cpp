// `rumble run FILE`: validate, then run; results in the scenario's outputs.directory.
#include <unistd.h>

#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/logging.hpp"
#include "run/interrupt.hpp"
#include "run/run_scenario.hpp"

namespace rumble::cli {

int run_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"no-progress"}, {});
  if (a.positional().size() != 1) throw UsageError("usage: rumble run FILE [--no-progress]");
  PluginRegistry registry;
  const auto doc = prepare_scenario(a.positional()[0], registry, scenario::Format::kText);
  if (!doc) return kExitConfig;
  install_interrupt_handler();
  RunOptions options;
  options.progress = !a.flag("no-progress") && isatty(STDERR_FILENO) != 0;
  const RunOutcome outcome = run_scenario(doc->json, doc->path, registry, options);
  const auto log = logger("engine");
  if (outcome.exit_code == kExitOk) {
    log->info("run completed; results in {}", outcome.results_dir.string());
  } else {
    std::cerr << "rumble: error: " << outcome.message << '\n'
              << "rumble: note: results computed so far are in " << outcome.results_dir.string()
              << " (summary.json status \"" << outcome.status << "\")\n";
  }
  return outcome.exit_code;
}

}  // namespace rumble::cli
