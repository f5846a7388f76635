// `rumble run FILE`: validate, then run; results in the scenario's outputs.directory.
#include <unistd.h>

#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plot_script.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"
#include "parallel/mpi_session.hpp"
#include "post/post_run.hpp"
#include "run/run_scenario.hpp"
#include "scenario/report.hpp"

namespace rumble::cli {

namespace {

/// The scenario checked and its soils built (prepare_scenario: `doc` empty when it is refused).
/// Ctrl-C and SIGTERM are answered from here on: the validation builds the soils, and a FEM soil
/// meshes there (minutes for a large mesh, inside gmsh, which cannot be stopped between its
/// steps), so a signal then ends the process at the grace deadline with a message naming the
/// phase (core/interrupt.hpp) instead of the signal's silent default. False: a signal came and
/// the validation ended within the grace; nothing was written.
bool validated(const std::string& file, PluginRegistry& registry,
               const std::vector<scenario::Override>& overrides,
               const scenario::CheckOptions& check, std::optional<scenario::Document>& doc) {
  install_interrupt_handler();
  {
    const StopPhase phase("the scenario's validation (the soils built, a FEM soil meshed)");
    doc = prepare_scenario(file, registry, scenario::Format::kText, overrides, check);
  }
  if (!interrupt_requested()) return true;
  std::cerr << "rumble: error: stopped by " << interrupt_cause()
            << " during the scenario's validation, before the run began; nothing was written\n";
  return false;
}

}  // namespace

int run_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"no-progress", "no-plots", "overwrite", "allow-outside-results", "yes"},
                    {"output"}, {"set"});
  if (a.positional().size() != 1) {
    throw UsageError(
        "usage: rumble run FILE [--output DIR] [--overwrite] [--allow-outside-results] [--yes] "
        "[--no-progress] [--no-plots] [--set POINTER=VALUE ...]");
  }
  std::vector<scenario::Override> overrides;
  for (const std::string& set : a.values("set"))
    overrides.push_back(scenario::parse_set_option(set));
  const auto output = a.directory("output", "its results");  // before anything is checked
  PluginRegistry registry;
  scenario::CheckOptions check;
  check.size_confirmed = a.flag("yes");  // a run beyond the size limits (scenario/run_size.hpp)
  check_results_directory(check, output.has_value(), a.flag("allow-outside-results"));
  check.machine_room = true;  // the memory and disk free now (scenario/run_size.hpp)
  const std::filesystem::path output_directory = output ? std::filesystem::absolute(*output) : "";
  if (output) check.output_directory = &output_directory;
  BuiltSoils built;  // the soils validation builds, for the run (a FEM soil is built once)
  check.keep_soils = &built;
  check.ranks = parallel::world_size();  // (under mpirun, MPI started before the command)
  std::optional<scenario::Document> doc;
  if (!validated(a.positional()[0], registry, overrides, check, doc)) return kExitRunFailed;
  if (!doc) return kExitConfig;
  if (output)  // overrides outputs.directory: the user's choice
    doc->json["outputs"]["directory"] = std::filesystem::absolute(*output).string();
  if (a.flag("no-plots")) doc->json["outputs"]["plots"] = false;
  RunOptions options;
  options.built_soils = &built;
  options.size_confirmed = check.size_confirmed;
  options.progress = !a.flag("no-progress") && isatty(STDERR_FILENO) != 0;
  scenario::RunSpec spec = scenario::make_run_spec(doc->json, doc->path);
  std::vector<std::string> identity;  // the same file with other --set values is another run
  for (const scenario::Override& o : overrides) {
    spec.overrides.push_back({{"pointer", o.pointer}, {"value", o.value}});
    identity.push_back(scenario::override_text(o));
  }
  // Locked, and the previous run's listed files removed; until the plots are done.
  ResultsDirectory results(spec.outputs.directory, spec.path, a.flag("overwrite"), identity);
  const RunOutcome outcome = run_scenario(spec, registry, results, options);
  const auto log = logger("engine");
  // A failed run (diverged, a participant's error) is post-processed too, up to where it got:
  // the PPV of a diverging run is how the seed paper shows its divergence. Not after Ctrl-C.
  const bool post = outcome.status == RunStatus::kCompleted || outcome.status == RunStatus::kFailed;
  if (post && std::filesystem::exists(outcome.results_dir / "receivers.csv")) {
    const StopPhase phase("post-processing");
    try {
      post_process_run(outcome.results_dir, post::options_from_scenario(doc->json));
    } catch (const std::exception& e) {  // the run's own results are on disk: say, go on
      log->warn(
          "post-processing failed: {}; the run's results are on disk (rumble post {} retries)",
          e.what(), outcome.results_dir.lexically_normal().string());
    }
  }
  // Not after Ctrl-C either: the user asked to stop (the plots take seconds).
  if (outcome.status == RunStatus::kCompleted && spec.outputs.plots) {
    const StopPhase phase("the plots");
    run_plot_script("plot_results.py", outcome.results_dir);
  }
  // Printed as "results/x", not "scenarios/paper/../../results/x"; only printed: lexically
  // dropping "dir/.." is wrong when dir is a symbolic link, so the path written to is not.
  const std::string shown = outcome.results_dir.lexically_normal().string();
  if (outcome.exit_code == kExitOk) {
    log->info("run completed; results in {}", shown);
  } else {
    std::cerr << "rumble: error: " << outcome.message << '\n'
              << "rumble: note: results computed so far are in " << shown
              << " (summary.json status \"" << status_name(outcome.status) << "\")\n";
  }
  return outcome.exit_code;
}

}  // namespace rumble::cli
