// The fuzz targets' checks (<name>_check.hpp) in the presets without libFuzzer, on every seed of
// each target and every input a fuzzer found a defect with (regressions/<name>/), so that a fixed
// defect stays fixed without clang. The expected messages of those inputs are golden cases or
// unit tests where the message comes from (docs/fuzzing.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#include "mesh/gmsh_model.hpp"
#include "msh_check.hpp"
#include "post_check.hpp"
#include "scenario_check.hpp"
#include "set_check.hpp"
#include "study_check.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;
using Check = std::function<std::string(std::string_view)>;

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::exists(dir)) return files;  // regressions/<name>: there once a defect was found
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void replay(const Check& check, const fs::path& dir, std::size_t at_least) {
  std::size_t n = 0;
  for (const fs::path& f : files_under(dir)) {
    EXPECT_EQ(check(read_file(f)), "") << f;
    ++n;
  }
  EXPECT_GE(n, at_least) << dir;
}

const fs::path kFuzz = source_dir() / "tests" / "fuzz";

TEST(ScenarioFuzzReplay, Regressions) {
  replay(check_scenario_text, kFuzz / "regressions" / "scenario", 1);
}

TEST(ScenarioFuzzReplay, Seeds) {
  const fs::path root = source_dir();
  replay(check_scenario_text, root / "tests" / "scenario" / "valid", 1);
  replay(check_scenario_text, root / "tests" / "scenario" / "invalid", 10);
  replay(check_scenario_text, root / "scenarios", 10);
}

// Texts that are refused or wrong still hold every property (refused with a diagnostic).
TEST(ScenarioFuzzReplay, MalformedInputsHoldTheProperties) {
  EXPECT_EQ(check_scenario_text("{"), "");   // a syntax error
  EXPECT_EQ(check_scenario_text("[]"), "");  // not an object: a schema finding
}

TEST(SetFuzzReplay, Regressions) {
  replay(check_set_option, kFuzz / "regressions" / "set", 0);
}

TEST(SetFuzzReplay, Seeds) {
  replay(check_set_option, kFuzz / "corpus" / "set", 30);
}

TEST(StudyFuzzReplay, Regressions) {
  replay(check_study_text, kFuzz / "regressions" / "study", 0);
}

TEST(StudyFuzzReplay, Seeds) {
  replay(check_study_text, kFuzz / "corpus" / "study", 40);
}

TEST(PostFuzzReplay, Regressions) {
  replay(check_post_input, kFuzz / "regressions" / "post", 0);
}

TEST(PostFuzzReplay, Seeds) {
  replay(check_post_input, kFuzz / "corpus" / "post", 25);
}

TEST(MshFuzzReplay, Regressions) {
  replay(check_msh_text, kFuzz / "regressions" / "msh", 0);
}

TEST(MshFuzzReplay, Seeds) {
  replay(check_msh_text, kFuzz / "corpus" / "msh", 10);
}

// Found by the campaign on the bytes as they are (msh_raw_fuzzer), fixed on Rumble's side.
TEST(MshFuzzReplay, RawRegressions) {
  replay(check_raw_msh_text, kFuzz / "regressions" / "msh_raw", 1);
}

// The seeds reach the end of the import: the box is a mesh of the track's one sleeper.
TEST(MshFuzzReplay, TheBoxSeedIsAMeshOfTheTrack) {
  const std::string path = (kFuzz / "corpus" / "msh" / "box_one_footprint").string();
  const fem::MeshFile file = fem::load_mesh_file(msh_default_settings(), path);
  EXPECT_EQ(file.mesh.tets.size(), 54u);
  EXPECT_EQ(file.footprints.size(), 1u);
  EXPECT_NO_THROW(fem::check_mesh_footprints(file, {{0.0, 0.0, 2.6, 0.26}}));
}

}  // namespace
}  // namespace rumble::fuzz
