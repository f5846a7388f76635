// A library with a manifest (plugin/manifest.hpp) is registered from it and loaded at the first
// use of one of its factories; a manifest of another build, or a damaged one, is ignored; a
// library that differs from its manifest is refused at that first use, with what differs.
#include "plugin/manifest.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.hpp"
#include "fixture_paths.hpp"
#include "plugin/registry.hpp"

namespace {

namespace fs = std::filesystem;
using rumble::PluginRegistry;

/// A fresh directory for one test.
fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("rumble_manifest_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A copy of the fixture `library` in `dir`, as `name`.
fs::path copy_of(const fs::path& library, const fs::path& dir, const std::string& name) {
  const fs::path copy = dir / name;
  fs::copy_file(library, copy);
  return copy;
}

/// The manifest of `library` as `rumble plugins --manifest` writes it.
std::string manifest_of(const fs::path& library) {
  PluginRegistry registry(PluginRegistry::Manifests::kIgnore);
  registry.load_library(library);
  return rumble::manifest_text(*registry.libraries().front(), registry.types());
}

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

/// A copy of the faulty fixture with its manifest beside it, in `dir`.
fs::path faulty_with_its_manifest(const fs::path& dir) {
  const fs::path library = copy_of(fixture::faulty, dir, "faulty.so");
  write(rumble::manifest_path(library), manifest_of(library));
  return library;
}

TEST(PluginManifest, TheTypesComeFromItAndTheLibraryLoadsAtItsFirstUse) {
  const fs::path dir = scratch("lazy");
  const fs::path library = faulty_with_its_manifest(dir);

  PluginRegistry eager(PluginRegistry::Manifests::kIgnore);
  eager.load_library(library);
  PluginRegistry registry;
  registry.load_library(library);
  ASSERT_EQ(registry.types().size(), eager.types().size());
  const rumble::ComponentType& type = registry.types().front();
  EXPECT_FALSE(type.library->loaded()) << "the manifest said what loading would have";
  EXPECT_EQ(type.library->identity.name, eager.libraries().front()->identity.name);
  EXPECT_EQ(type.library->identity.abi(), eager.libraries().front()->identity.abi());
  EXPECT_EQ(rumble::manifest_difference(type, eager.types().front()), "");

  const rumble_factory& factory = type.factory();
  EXPECT_TRUE(type.library->loaded());
  EXPECT_STREQ(factory.type_name, "loader_test_faulty");
  fs::remove_all(dir);
}

TEST(PluginManifest, OneOfAnotherBuildOrDamagedIsIgnored) {
  const fs::path dir = scratch("ignored");
  const fs::path library = copy_of(fixture::raw, dir, "raw.so");
  PluginRegistry eager(PluginRegistry::Manifests::kIgnore);
  eager.load_library(library);
  for (const std::string& text :
       {manifest_of(fixture::faulty), std::string("{\"types\": ["), std::string("[]")}) {
    write(rumble::manifest_path(library), text);
    PluginRegistry registry;
    registry.load_library(library);
    ASSERT_EQ(registry.types().size(), eager.types().size()) << text;
    EXPECT_TRUE(registry.libraries().front()->loaded()) << "loaded to learn its types: " << text;
    EXPECT_EQ(registry.types().front().type_name, eager.types().front().type_name);
  }
  fs::remove_all(dir);
}

TEST(PluginManifest, ALibraryThatDiffersFromItIsRefusedAtItsFirstUse) {
  const fs::path dir = scratch("differs");
  const fs::path library = copy_of(fixture::faulty, dir, "faulty.so");
  auto manifest = nlohmann::json::parse(manifest_of(library));
  manifest["types"][0]["summary"] = "what an older build said";
  write(rumble::manifest_path(library), manifest.dump());

  PluginRegistry registry;
  registry.load_library(library);
  const rumble::ComponentType& type = registry.types().front();
  EXPECT_EQ(type.summary, "what an older build said");
  try {
    type.factory();
    FAIL() << "a library unlike its manifest was used";
  } catch (const rumble::PluginLoadError& e) {
    const std::string canonical = fs::canonical(library).string();
    EXPECT_EQ(std::string(e.what()),
              "plugin '" + canonical + "': not what its manifest '" + canonical +
                  ".manifest.json' lists (type 'loader_test_faulty': its summary differs); "
                  "rebuild the plugin, whose build writes the manifest, or delete the manifest");
  }
  EXPECT_FALSE(type.library->loaded()) << "nothing of it is used";
  fs::remove_all(dir);
}

TEST(PluginManifest, IgnoredWhereEveryLibraryMustBeLoaded) {
  const fs::path dir = scratch("kignore");
  const fs::path library = faulty_with_its_manifest(dir);
  PluginRegistry registry(PluginRegistry::Manifests::kIgnore);
  registry.load_library(library);
  EXPECT_TRUE(registry.libraries().front()->loaded());
  fs::remove_all(dir);
}

TEST(PluginManifest, TheBuildIdIsTheLinkersAndKeptByACopy) {
  const std::string id = rumble::elf_build_id(fixture::faulty);
  EXPECT_GE(id.size(), 16u) << "the linker wrote no build ID; manifests are never used";
  EXPECT_EQ(id.find_first_not_of("0123456789abcdef"), std::string::npos) << id;
  EXPECT_NE(id, rumble::elf_build_id(fixture::raw));
  const fs::path dir = scratch("build_id");
  EXPECT_EQ(rumble::elf_build_id(copy_of(fixture::faulty, dir, "copy.so")), id);
  write(dir / "text.so", "not an ELF file");
  EXPECT_EQ(rumble::elf_build_id(dir / "text.so"), "");
  EXPECT_EQ(rumble::elf_build_id(dir / "absent.so"), "");
  fs::remove_all(dir);
}

// Every in-tree plugin's build wrote the manifest of the very library beside it.
TEST(PluginManifest, EveryInTreePluginHasOneThatIsUsed) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  ASSERT_GE(registry.libraries().size(), 10u);
  for (const auto& library : registry.libraries())
    EXPECT_FALSE(library->loaded()) << library->path << ": its manifest was not used";
}

}  // namespace
