// The front half of `rumble run` and `rumble validate`: load the plugins, read the scenario,
// validate it completely (schema, plugin params, engine relations) and print every finding.
#pragma once

#include <filesystem>
#include <optional>

#include "plugin/registry.hpp"
#include "scenario/scenario.hpp"

namespace rumble::cli {

/// Returns the validated document (defaults filled), or nullopt when anything is wrong (the
/// diagnostics have been printed). Throws PluginLoadError when a plugin cannot be loaded.
std::optional<scenario::Document> prepare_scenario(const std::filesystem::path& path,
                                                   PluginRegistry& registry,
                                                   scenario::Format format);

}  // namespace rumble::cli
