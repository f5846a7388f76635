// Every way a library can fail to register, with the loader's exact message, and the registry
// left as it was. The fixtures are built by this directory's CMakeLists.txt (fixture_paths.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.hpp"
#include "fixture_paths.hpp"
#include "plugin/registry.hpp"

namespace {

namespace fs = std::filesystem;
using rumble::PluginRegistry;

/// The PluginLoadError text of loading `path`, or a marker when it loaded.
std::string load_error(PluginRegistry& registry, const fs::path& path) {
  try {
    registry.load_library(path);
  } catch (const rumble::PluginLoadError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

/// How the loader quotes a path it has resolved.
std::string quoted(const fs::path& path) {
  return "'" + fs::canonical(path).string() + "'";
}

const std::string kHostAbi =
    std::to_string(RUMBLE_ABI_MAJOR) + "." + std::to_string(RUMBLE_ABI_MINOR);

TEST(PluginLoadErrors, FileNotFound) {
  PluginRegistry registry;
  const fs::path missing = fs::path(fixture::dir) / "no_such_plugin.so";
  EXPECT_EQ(load_error(registry, missing),
            "plugin '" + missing.string() +
                "': file not found; check the path (relative paths are relative to the scenario "
                "file) or RUMBLE_PLUGIN_PATH");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, NotASharedLibrary) {
  // Longer than an ELF header, so that the loader gets as far as reading one.
  const fs::path fake = fs::path(fixture::dir) / "loader_not_elf.so";
  std::ofstream(fake) << std::string(200, '#') << "\nthis is a text file named like a plugin\n";
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fake), "plugin " + quoted(fake) + ": cannot be loaded: " +
                                            fs::canonical(fake).string() + ": invalid ELF header");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, UnresolvedSymbolFailsAtLoadNotLater) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::unresolved),
            "plugin " + quoted(fixture::unresolved) +
                ": cannot be loaded: " + fs::canonical(fixture::unresolved).string() +
                ": undefined symbol: rumble_test_missing_host_symbol");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, NoEntryPoint) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::no_entry),
            "plugin " + quoted(fixture::no_entry) +
                ": not a Rumble plugin (no 'rumble_plugin_entry' entry point); was it built with "
                "rumble_add_plugin() and RUMBLE_PLUGIN()?");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, EntryPointReturnsNull) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::null_descriptor),
            "plugin " + quoted(fixture::null_descriptor) + ": entry point returned no descriptor");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, WrongAbiMajor) {
  PluginRegistry registry;
  const std::string plugin_abi = std::to_string(RUMBLE_ABI_MAJOR + 1) + ".0";
  EXPECT_EQ(load_error(registry, fixture::wrong_abi_major),
            "plugin " + quoted(fixture::wrong_abi_major) + ": built for plugin ABI " + plugin_abi +
                ", this engine has ABI " + kHostAbi +
                " (the major versions differ); rebuild the plugin against Rumble SDK " +
                std::to_string(RUMBLE_ABI_MAJOR) + ".x");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, NewerAbiMinor) {
  PluginRegistry registry;
  const std::string plugin_abi =
      std::to_string(RUMBLE_ABI_MAJOR) + "." + std::to_string(RUMBLE_ABI_MINOR + 1);
  EXPECT_EQ(load_error(registry, fixture::newer_abi_minor),
            "plugin " + quoted(fixture::newer_abi_minor) + ": built for plugin ABI " + plugin_abi +
                ", newer than this engine's ABI " + kHostAbi +
                "; upgrade Rumble or rebuild the plugin against this engine's SDK");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, ShortDescriptor) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::short_descriptor),
            "plugin " + quoted(fixture::short_descriptor) +
                ": malformed descriptor (struct_size 8 bytes, ABI 1.0 needs 56); build the plugin "
                "with RUMBLE_PLUGIN() from the Rumble SDK");
  EXPECT_TRUE(registry.libraries().empty());
}

TEST(PluginLoadErrors, UnknownComponentKind) {
  PluginRegistry registry;
  EXPECT_EQ(
      load_error(registry, fixture::unknown_kind),
      "plugin " + quoted(fixture::unknown_kind) +
          ": factory 0 ('loader_test_forged') is malformed: unknown kind 99; build the plugin with "
          "RUMBLE_PLUGIN() from the Rumble SDK");
  EXPECT_TRUE(registry.types().empty());
}

TEST(PluginLoadErrors, ShortFactory) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::short_factory),
            "plugin " + quoted(fixture::short_factory) +
                ": factory 0 is malformed: struct_size 8 bytes, ABI 1.0 needs 48; build the "
                "plugin with RUMBLE_PLUGIN() from the Rumble SDK");
  EXPECT_TRUE(registry.types().empty());
}

TEST(PluginLoadErrors, FunctionTableWithoutARequiredFunction) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::no_advance),
            "plugin " + quoted(fixture::no_advance) +
                ": factory 0 ('loader_test_forged') is malformed: function table has no "
                "'advance'; build the plugin with RUMBLE_PLUGIN() from the Rumble SDK");
  EXPECT_TRUE(registry.types().empty());
}

// ABI 1.1: a capability declared without the functions it needs is refused at load, not a null
// call when the engine relies on the declaration.
TEST(PluginLoadErrors, DeclaredCapabilityWithoutItsFunction) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::unbacked_capability),
            "plugin " + quoted(fixture::unbacked_capability) +
                ": factory 0 ('loader_test_forged') is malformed: declares receivers but its "
                "function table has no 'set_probes'; build the plugin with RUMBLE_PLUGIN() from "
                "the Rumble SDK");
  EXPECT_TRUE(registry.types().empty());
}

TEST(PluginLoadErrors, MalformedCapabilities) {
  PluginRegistry registry;
  const std::string tail = "; build the plugin with RUMBLE_PLUGIN() from the Rumble SDK";
  EXPECT_EQ(load_error(registry, fixture::bad_participants),
            "plugin " + quoted(fixture::bad_participants) +
                ": factory 0 ('loader_test_forged') is malformed: capabilities participants_json "
                "is not a JSON object" +
                tail);
  EXPECT_EQ(load_error(registry, fixture::negative_max_step),
            "plugin " + quoted(fixture::negative_max_step) +
                ": factory 0 ('loader_test_forged') is malformed: capabilities max_macro_step is "
                "negative or NaN" +
                tail);
  // ABI 1.2: only a coupler can ask for the soil to be integrated with the track.
  EXPECT_EQ(load_error(registry, fixture::monolithic_soil),
            "plugin " + quoted(fixture::monolithic_soil) +
                ": factory 0 ('loader_test_forged') is malformed: capability MONOLITHIC is for "
                "couplers only" +
                tail);
  EXPECT_TRUE(registry.types().empty());
}

TEST(PluginLoadErrors, NoFactories) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::no_factories),
            "plugin " + quoted(fixture::no_factories) +
                ": provides no component types (n_factories is 0); list the plugin's classes in "
                "RUMBLE_PLUGIN(name, version, Classes...)");
  EXPECT_TRUE(registry.libraries().empty());
}

// The same C source without a forged defect loads: the failures above are the defects only.
TEST(PluginLoadErrors, UnforgedCDescriptorLoads) {
  PluginRegistry registry;
  ASSERT_NO_THROW(registry.load_library(fixture::forged_ok));
  ASSERT_NE(registry.find(RUMBLE_KIND_SOIL, "loader_test_forged"), nullptr);
  EXPECT_EQ(registry.libraries().at(0)->descriptor->abi_major, unsigned{RUMBLE_ABI_MAJOR});
}

TEST(PluginLoadErrors, DuplicateTypeAcrossLibraries) {
  PluginRegistry registry;
  ASSERT_NO_THROW(registry.load_library(fixture::dup_a));
  EXPECT_EQ(load_error(registry, fixture::dup_b),
            "plugin " + quoted(fixture::dup_b) +
                ": type 'loader_test_dup' is already provided "
                "by " +
                quoted(fixture::dup_a) +
                "; type names must be unique: rename one, or remove one library from the plugin "
                "path");
  // The first library keeps its type; nothing of the second is registered.
  ASSERT_EQ(registry.libraries().size(), 1u);
  EXPECT_EQ(registry.find(RUMBLE_KIND_SOIL, "loader_test_dup")->library->path,
            fs::canonical(fixture::dup_a));
}

// Directory scans load in sorted order, so which library is reported does not depend on the
// file system's order.
TEST(PluginLoadErrors, DuplicateTypeInDirectoryIsDeterministic) {
  PluginRegistry registry;
  EXPECT_THROW(
      {
        try {
          registry.load_directory(fs::path(fixture::dir) / "duplicate");
        } catch (const rumble::PluginLoadError& e) {
          EXPECT_EQ(std::string(e.what()).rfind("plugin " + quoted(fixture::dup_b) + ":", 0), 0u)
              << e.what();
          throw;
        }
      },
      rumble::PluginLoadError);
}

TEST(PluginLoadErrors, DuplicateTypeWithinOneLibrary) {
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fixture::dup_within),
            "plugin " + quoted(fixture::dup_within) +
                ": type 'loader_test_dup' is already "
                "provided by " +
                quoted(fixture::dup_within) +
                "; type names must be unique: rename one, or remove one library from the plugin "
                "path");
  EXPECT_TRUE(registry.types().empty());
}

// Loading the same file twice (e.g. named in RUMBLE_PLUGIN_PATH and in the scenario) is no error.
TEST(PluginLoadErrors, SameLibraryTwiceIsLoadedOnce) {
  PluginRegistry registry;
  registry.load_library(fixture::dup_a);
  EXPECT_NO_THROW(registry.load_library(fixture::dup_a));
  EXPECT_EQ(registry.libraries().size(), 1u);
}

// RUMBLE_PLUGIN_PATH entries may be files; a missing one is reported, not skipped.
TEST(PluginLoadErrors, MissingFileInPluginPath) {
  const std::string missing = std::string(fixture::dir) + "/not_there.so";
  ASSERT_EQ(setenv("RUMBLE_PLUGIN_PATH", (std::string(fixture::faulty) + ":" + missing).c_str(), 1),
            0);
  PluginRegistry registry;
  try {
    registry.load_default_directories();
    FAIL() << "no error for " << missing;
  } catch (const rumble::PluginLoadError& e) {
    EXPECT_EQ(std::string(e.what()), "plugin '" + missing +
                                         "': file not found; check the path (relative paths are "
                                         "relative to the scenario file) or RUMBLE_PLUGIN_PATH");
  }
  EXPECT_NE(registry.find(RUMBLE_KIND_SOIL, "loader_test_faulty"), nullptr);
}

}  // namespace
