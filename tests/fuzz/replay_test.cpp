// The fuzz target's checks (scenario_check.hpp) in the dev build, on every seed of the fuzz
// campaign and every input it found a defect with (regressions/), so that a fixed defect stays
// fixed without clang. The expected messages of those inputs are golden cases in
// tests/scenario/invalid/.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "scenario_check.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void replay(const fs::path& dir, std::size_t at_least) {
  std::size_t n = 0;
  for (const fs::path& f : files_under(dir)) {
    EXPECT_EQ(check_scenario_text(read(f)), "") << f;
    ++n;
  }
  EXPECT_GE(n, at_least) << dir;
}

TEST(ScenarioFuzzReplay, Regressions) {
  replay(fs::path(RUMBLE_TEST_SOURCE_DIR) / "tests" / "fuzz" / "regressions", 0);
}

TEST(ScenarioFuzzReplay, Seeds) {
  const fs::path root(RUMBLE_TEST_SOURCE_DIR);
  replay(root / "tests" / "scenario" / "valid", 1);
  replay(root / "tests" / "scenario" / "invalid", 10);
  replay(root / "scenarios", 10);
}

// Texts that are refused or wrong still hold every property (refused with a diagnostic).
TEST(ScenarioFuzzReplay, MalformedInputsHoldTheProperties) {
  EXPECT_EQ(check_scenario_text("{"), "");   // a syntax error
  EXPECT_EQ(check_scenario_text("[]"), "");  // not an object: a schema finding
}

}  // namespace
}  // namespace rumble::fuzz
