// Shared helpers of the scenario tests: paths, the plugin registry they validate against, and
// the plugins a case needs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plugin/registry.hpp"

namespace rumble::scenario::test {

std::filesystem::path source_dir();
std::filesystem::path scenario_test_dir();  // tests/scenario in the source tree

/// The in-tree plugins the golden cases are written against (single_wheel, winkler,
/// gauss_seidel, jacobi), loaded from RUMBLE_TEST_PLUGIN_DIR. Only libraries providing one of
/// these types are loaded, so that the "known types" lists in the expected output do not
/// change each time another plugin is added to the tree.
const PluginRegistry& golden_registry();

struct Requirement {
  rumble_kind kind;
  std::string type;
};

/// "" when every requirement is in the registry; otherwise a message naming the missing ones.
std::string missing_plugins(const PluginRegistry& registry, const std::vector<Requirement>& needs);

/// The types minimal.json uses.
const std::vector<Requirement>& minimal_needs();

std::string read_file(const std::filesystem::path& path);

}  // namespace rumble::scenario::test
