// Everything `rumble validate` checks, without printing: read the file, apply the values set from
// outside it (--set, a study's patches), load the plugins it lists, validate it against the
// schemas, check the engine's relations and build the components. Used by `rumble validate`,
// `rumble run` (cli/scenario_prepare) and `rumble study` (every run before any runs).
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "scenario/capability_check.hpp"
#include "scenario/diagnostic.hpp"
#include "scenario/document.hpp"
#include "scenario/overrides.hpp"

namespace rumble {
class BuiltSoils;
class PluginRegistry;
}  // namespace rumble

namespace rumble::scenario {

/// What to check beyond the file itself.
struct CheckOptions {
  /// false (`rumble validate --no-load`): no library of /plugins is loaded and no component is
  /// built, so no plugin code runs; component types and params go unchecked.
  bool load_plugins = true;
  /// true (`--yes`): a run estimated beyond the size limits (scenario/run_size.hpp) is wanted.
  bool size_confirmed = false;
  /// false when the command line names another results directory (`run --output DIR`) or the
  /// command writes none: outputs.directory need not be usable then.
  bool results_directory = true;
  /// true (`rumble run` without --output or --allow-outside-results): outputs.directory outside
  /// the scenario's folder is an error, found before any component is built (a FEM soil meshes
  /// in its constructor, for minutes on a large mesh).
  bool results_inside_folder = false;
  /// When given, the soils built by the check stay here for the run or command that follows in
  /// the same process (a FEM soil is then meshed and assembled once, not twice).
  BuiltSoils* keep_soils = nullptr;
  /// true (`rumble run`): the run's estimate is also held against the memory and the disk this
  /// machine has free now (check_machine_room), the disk's under `output_directory` when given,
  /// else under outputs.directory. Not in `validate`: a scenario may be meant for another machine.
  bool machine_room = false;
  const std::filesystem::path* output_directory = nullptr;  // (a pointer: kNotARun is constexpr)
  /// The MPI ranks of this launch (`mpirun -n N`, on rank 0), over which a distributed soil is
  /// split: what needs its whole matrices is refused before it is built (check_split_soil).
  int ranks = 1;
  /// The command, where it reads the soil's whole operator (`rumble stability`, `soil-frf`,
  /// `calibrate`): refused before the soil is built when the soil is split over `ranks`.
  WholeSoilCommand whole_soil{};
};

struct CheckedScenario {
  std::optional<Document> doc;  // nullopt when the file could not be read or parsed
  std::vector<Diagnostic> diagnostics;
  /// Read, and no error among the diagnostics (warnings allowed).
  bool ok() const;
};

/// Reads and checks `path` with `overrides` applied in order (their applied_at is set), defaults
/// filled into doc.json; diagnostics about a value an override set end with its note
/// ("(set by --set)"). Throws ConfigError when an override cannot be applied, PluginLoadError
/// when a plugin library the scenario lists cannot be loaded. The registry should hold the
/// default plugin directories already. The run's estimated size is checked last.
CheckedScenario check_scenario_file(const std::filesystem::path& path,
                                    std::vector<Override>& overrides, PluginRegistry& registry,
                                    const CheckOptions& options = {});

/// The same checks on a document already read and parsed (parse_document): everything after
/// load_document. The fuzz target (tests/fuzz) checks text from memory this way.
CheckedScenario check_scenario_document(Document doc, std::vector<Override>& overrides,
                                        PluginRegistry& registry, const CheckOptions& options = {});

}  // namespace rumble::scenario
