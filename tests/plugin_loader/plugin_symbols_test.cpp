// Every in-tree plugin exports exactly one dynamic symbol, rumble_plugin_entry, and no
// STB_GNU_UNIQUE symbol. A second export can clash with the host or another plugin (RTLD_LOCAL
// limits but does not remove that); a UNIQUE one makes glibc mark the library NODELETE, which
// hides lifetime bugs in some builds and not in others (docs/toolchain.md §3).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "elf_symbols.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> in_tree_plugins() {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(RUMBLE_TEST_PLUGIN_DIR)) {
    if (e.path().extension() == ".so") found.push_back(e.path());
  }
  return found;
}

TEST(PluginSymbols, InTreePluginsExist) {
  EXPECT_FALSE(in_tree_plugins().empty()) << "no *.so in " << RUMBLE_TEST_PLUGIN_DIR;
}

TEST(PluginSymbols, InTreePluginsExportOnlyTheEntryPoint) {
  for (const fs::path& plugin : in_tree_plugins()) {
    const auto symbols = rumble::test::defined_dynamic_symbols(READELF, plugin.string());
    const bool has_entry = std::any_of(symbols.begin(), symbols.end(), [](const auto& s) {
      return s.name == "rumble_plugin_entry" && s.type == "FUNC";
    });
    EXPECT_TRUE(has_entry) << plugin << " does not export rumble_plugin_entry";
    EXPECT_EQ(symbols.size(), 1u) << plugin << " exports more than its entry point:\n"
                                  << rumble::test::describe(symbols);
  }
}

TEST(PluginSymbols, InTreePluginsHaveNoUniqueSymbols) {
  for (const fs::path& plugin : in_tree_plugins()) {
    std::vector<rumble::test::DynamicSymbol> unique;
    for (const auto& s : rumble::test::defined_dynamic_symbols(READELF, plugin.string())) {
      if (s.bind == "UNIQUE") unique.push_back(s);
    }
    EXPECT_TRUE(unique.empty()) << plugin << " has STB_GNU_UNIQUE symbols (the library can "
                                << "never be unloaded):\n"
                                << rumble::test::describe(unique);
  }
}

}  // namespace
