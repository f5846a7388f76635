// Every way a library can fail to register, with the loader's exact message, and the registry
// left as it was. The fixtures are built by this directory's CMakeLists.txt (fixture_paths.hpp).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.hpp"
#include "fixture_paths.hpp"
#include "plugin/function_table.hpp"
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

// ABI 1.7: never_refuses promises that a participant's advance takes every step; a coupler has
// no advance to refuse, so declaring it there is a malformed factory. (A vehicle or soil
// declaring it is checked where it refuses anyway: DiscardRetry.APromiseNeverToRefuseIsHeldToIt.)
TEST(PluginLoadErrors, NeverRefusesIsForVehiclesAndSoils) {
  rumble_capabilities caps{};
  caps.struct_size = sizeof caps;
  caps.offers = RUMBLE_CAP_NEVER_REFUSES;
  rumble_factory f{};
  f.struct_size = sizeof f;
  f.capabilities = &caps;
  f.kind = RUMBLE_KIND_COUPLER;
  EXPECT_EQ(rumble::factory_capabilities_defect(f, 0),
            "capability NEVER_REFUSES is for vehicles and soils, whose advance could refuse");
  for (const rumble_kind kind : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL}) {
    f.kind = kind;
    EXPECT_EQ(rumble::factory_capabilities_defect(f, 0), "") << kind;
  }
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
  EXPECT_EQ(registry.libraries().at(0)->identity.abi_major, unsigned{RUMBLE_ABI_MAJOR});
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

// RUMBLE_PLUGIN_PATH entries may be files or directories; a missing one, or a library that does
// not load, is reported and skipped: the others still load (issue #8: one bad entry made every
// command fail, `rumble plugins` too).
TEST(PluginLoadErrors, BadEntriesInPluginPathAreSkippedAndReported) {
  const std::string missing = std::string(fixture::dir) + "/not_there.so";
  const std::string missing_dir = std::string(fixture::dir) + "/no_such_directory";
  const std::string path =
      std::string(fixture::no_entry) + ":" + missing + ":" + missing_dir + ":" + fixture::faulty;
  ASSERT_EQ(setenv("RUMBLE_PLUGIN_PATH", path.c_str(), 1), 0);
  PluginRegistry registry;
  ASSERT_NO_THROW(registry.load_default_directories());
  unsetenv("RUMBLE_PLUGIN_PATH");
  const rumble::ComponentType* faulty = registry.find(RUMBLE_KIND_SOIL, "loader_test_faulty");
  ASSERT_NE(faulty, nullptr);
  EXPECT_EQ(faulty->library->origin, "RUMBLE_PLUGIN_PATH");
  ASSERT_EQ(registry.skipped().size(), 3u);
  EXPECT_EQ(registry.skipped()[0].path, fs::path(fixture::no_entry));
  EXPECT_EQ(registry.skipped()[0].origin, "RUMBLE_PLUGIN_PATH");
  EXPECT_EQ(registry.skipped()[0].reason.rfind(
                "plugin " + quoted(fixture::no_entry) + ": not a Rumble plugin", 0),
            0u)
      << registry.skipped()[0].reason;
  EXPECT_EQ(registry.skipped()[1].reason,
            "RUMBLE_PLUGIN_PATH entry '" + missing +
                "': no such file or directory; correct or remove the entry");
  EXPECT_EQ(registry.skipped()[2].reason,
            "RUMBLE_PLUGIN_PATH entry '" + missing_dir +
                "': no such file or directory; correct or remove the entry");
}

// dlopen on a FIFO blocks until someone writes to it (validate and run hung): only regular files
// are loaded, whatever their name.
TEST(PluginLoadErrors, FifoAndDirectoryAreNotLibraries) {
  const fs::path fifo = fs::path(fixture::dir) / "loader_fifo.so";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  PluginRegistry registry;
  EXPECT_EQ(load_error(registry, fifo),
            "plugin '" + fifo.string() +
                "': a FIFO (named pipe), not a regular file; name a shared library (.so) file");
  fs::remove(fifo);
  EXPECT_EQ(load_error(registry, fixture::dir),
            "plugin '" + std::string(fixture::dir) +
                "': a directory, not a regular file; name a shared library (.so) file");
  EXPECT_EQ(load_error(registry, "/dev/zero"),
            "plugin '/dev/zero': a device, not a regular file; name a shared library (.so) file");
  EXPECT_TRUE(registry.libraries().empty());
}

}  // namespace
