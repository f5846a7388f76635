// The front half of `rumble run` and `rumble validate`: load the plugins, read the scenario,
// validate it completely (schema, plugin params, engine relations) and print every finding.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "plugin/built_soils.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "scenario/check_file.hpp"
#include "scenario/overrides.hpp"
#include "scenario/scenario.hpp"

namespace rumble::cli {

/// Returns the validated document (defaults filled), or nullopt when anything is wrong (the
/// diagnostics have been printed). `overrides` (--set) are applied in order before validation.
/// Throws PluginLoadError when a plugin cannot be loaded, ConfigError when an override cannot be
/// applied. options.load_plugins false: not even the default plugin directories are loaded.
std::optional<scenario::Document> prepare_scenario(const std::filesystem::path& path,
                                                   PluginRegistry& registry,
                                                   scenario::Format format,
                                                   std::vector<scenario::Override> overrides = {},
                                                   const scenario::CheckOptions& options = {});

/// For the commands that build a scenario's parts without running it (mesh, soil-frf,
/// calibrate, stability): the run's size is no concern of theirs.
inline constexpr scenario::CheckOptions kNotARun{
    .load_plugins = true, .size_confirmed = true, .results_directory = false};

/// For the commands that write into the scenario's outputs.directory (run, mesh, soil-frf):
/// `output_given` (--output DIR) replaces it, the user's choice; without it, it must be usable
/// and, unless `allow_outside` (--allow-outside-results), inside the scenario's folder
/// (docs/scenario.md, "The results directory").
inline void check_results_directory(scenario::CheckOptions& check, bool output_given,
                                    bool allow_outside) {
  check.results_directory = !output_given;
  check.results_inside_folder = !output_given && !allow_outside;
}

/// The scenario's soil (/soil), built and laid on the track's footprints as a run lays it: what
/// `rumble mesh` and `rumble soil-frf` look at. Taken from `built` (the validation's, see
/// CheckOptions::keep_soils) when it holds it.
struct ScenarioSoil {
  std::vector<rumble_footprint> layout;
  const ComponentType* type = nullptr;
  std::unique_ptr<SoilInstance> soil;
};
ScenarioSoil soil_on_footprints(const scenario::Document& doc, const PluginRegistry& registry,
                                BuiltSoils* built = nullptr);

}  // namespace rumble::cli
