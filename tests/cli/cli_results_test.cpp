// What a run does with its results directory (issue #8): no write goes through a symbolic link.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

// ---- never through a link

// A link planted at a results file's name (contact.csv, the summary's temporary file) is
// replaced by the file; its target is never written.
TEST(CliResults, LinksInTheResultsDirectoryAreReplacedNeverFollowed) {
  const auto dir = scratch_directory("results_links");
  const auto path = write_scenario(dir, small_scenario());
  const auto results = dir / "results";
  fs::create_directories(results);
  for (const char* f : {"precious_csv.txt", "precious_tmp.txt"}) write_text(dir / f, "keep me");
  fs::create_symlink(dir / "precious_csv.txt", results / "contact.csv");
  fs::create_symlink(dir / "precious_tmp.txt", results / "summary.json.tmp");
  const CliResult r = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file_text(dir / "precious_csv.txt"), "keep me");
  EXPECT_EQ(file_text(dir / "precious_tmp.txt"), "keep me");
  EXPECT_FALSE(fs::is_symlink(results / "contact.csv"));
  EXPECT_EQ(csv_rows(results / "contact.csv"), 51u);
}

}  // namespace
}  // namespace rumble::testing
