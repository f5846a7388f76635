// A scenario or a command line never writes or deletes outside its results (issue 30): a results
// directory that leads out of the scenario's folder through a symbolic link is refused as one
// that leaves it with ".." is, by every command that writes there (docs/scenario.md, "The results
// directory").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

/// `dir`/sub/scenario.json writing to outputs.directory `results`, and `dir`/sub/`link` a symbolic
/// link to `dir`/elsewhere (made, empty): the scenario's path.
fs::path scenario_beside_link(const fs::path& dir, const std::string& results,
                              const std::string& link, const nlohmann::json& base) {
  fs::create_directories(dir / "sub");
  fs::create_directories(dir / "elsewhere");
  fs::create_directory_symlink(dir / "elsewhere", dir / "sub" / link);
  nlohmann::json s = base;
  s["outputs"]["directory"] = results;
  return write_scenario(dir / "sub", s);
}

TEST(CliPaths, AResultsDirectoryLeadingOutThroughALinkNeedsConsent) {
  const auto dir = scratch_directory("paths_results_link");
  const auto path = scenario_beside_link(dir, "results/run1", "results", small_scenario());
  const fs::path real = fs::canonical(dir);
  const CliResult refused = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output,
              HasSubstr("error: /outputs/directory: \"results/run1\" leads out of the scenario's "
                        "folder " +
                        (dir / "sub").string() + " through the symbolic link " +
                        (real / "sub" / "results").string() + " (it is " +
                        (real / "elsewhere" / "run1").string() + ")"));
  EXPECT_THAT(refused.output,
              HasSubstr("hint: results go inside the scenario's folder unless the command line "
                        "says otherwise: choose the directory with --output DIR, or pass "
                        "--allow-outside-results to write to " +
                        (real / "elsewhere" / "run1").string()));
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
  const CliResult allowed =
      run_rumble({"run", path.string(), "--no-progress", "--allow-outside-results"});
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_EQ(csv_rows(dir / "elsewhere" / "run1" / "contact.csv"), 51u);
}

// "new/../results" is "results" once "new" is made: the link is followed then, so it is here.
TEST(CliPaths, AMissingDirectoryAndDotDotDoNotHideALink) {
  const auto dir = scratch_directory("paths_results_dotdot");
  const auto path = scenario_beside_link(dir, "new/../out/x", "out", small_scenario());
  const CliResult refused = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("\"new/../out/x\" leads out of the scenario's folder"));
  EXPECT_FALSE(fs::exists(dir / "sub" / "new"));
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
}

// A link that stays inside the folder is a directory like another.
TEST(CliPaths, ALinkInsideTheFolderIsFollowed) {
  const auto dir = scratch_directory("paths_results_link_inside");
  fs::create_directories(dir / "real_results");
  fs::create_directory_symlink(dir / "real_results", dir / "results");
  const CliResult r =
      run_rumble({"run", write_scenario(dir, small_scenario()).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(csv_rows(dir / "real_results" / "contact.csv"), 51u);
}

// `rumble mesh` and `rumble soil-frf` write into outputs.directory too: the same rule, the same
// consent.
TEST(CliPaths, MeshAndSoilFrfKeepToTheScenariosFolder) {
  const auto dir = scratch_directory("paths_mesh_frf_link");
  const auto path = scenario_beside_link(dir, "results", "results", small_scenario()).string();
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"mesh", path},
        std::vector<std::string>{"soil-frf", path, "--points", "2", "--no-plot"}}) {
    const CliResult refused = run_rumble(command);
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_THAT(refused.output, HasSubstr("error: /outputs/directory: \"results\" leads out of the "
                                          "scenario's folder"));
    EXPECT_THAT(refused.output, HasSubstr("pass --allow-outside-results to write to"));
  }
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
  const CliResult frf =
      run_rumble({"soil-frf", path, "--points", "2", "--no-plot", "--allow-outside-results"});
  EXPECT_EQ(frf.exit_code, 0) << frf.output;
  EXPECT_TRUE(fs::exists(dir / "elsewhere" / "soil_frf" / "scenario_winkler.csv"));
  nlohmann::json absolute = small_scenario();
  absolute["outputs"]["directory"] = (dir / "absolute").string();
  const CliResult mesh = run_rumble({"mesh", write_scenario(dir, absolute).string()});
  EXPECT_EQ(mesh.exit_code, 1) << mesh.output;
  EXPECT_THAT(mesh.output, HasSubstr("is an absolute path"));
  EXPECT_FALSE(fs::exists(dir / "absolute"));
}

/// The FEM soil's mesh cache in the test's scratch directory.
RunSetup cache_in(const fs::path& dir) {
  RunSetup setup;
  setup.environment = {{"RUMBLE_MESH_CACHE", (dir / "cache").string()}};
  return setup;
}

// mesh.vtu is written as a new file: a link planted at its name is refused, never followed,
// and left as it is; an earlier mesh.vtu (a regular file) is replaced.
TEST(CliPaths, MeshNeverWritesThroughALink) {
  const auto dir = scratch_directory("paths_mesh_vtu_link");
  const auto path = write_scenario(dir, small_fem_scenario()).string();
  std::ofstream(dir / "precious.txt") << "keep me\n";
  fs::create_directories(dir / "results");
  fs::create_symlink(dir / "precious.txt", dir / "results" / "mesh.vtu");
  const CliResult refused = run_rumble({"mesh", path}, cache_in(dir));
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output,
              HasSubstr("rumble: error: " + (dir / "results" / "mesh.vtu").string() +
                        " is a symbolic link (to " + (dir / "precious.txt").string() +
                        "); rumble mesh writes mesh.vtu as a new file, never through a link nor "
                        "over anything but an earlier mesh.vtu: move it away, or choose another "
                        "directory with --output DIR"));
  EXPECT_EQ(file_text(dir / "precious.txt"), "keep me\n");
  EXPECT_TRUE(fs::is_symlink(dir / "results" / "mesh.vtu"));
  fs::remove(dir / "results" / "mesh.vtu");
  for (int k = 0; k < 2; ++k) {  // the second replaces the first's
    const CliResult r = run_rumble({"mesh", path}, cache_in(dir));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "results" / "mesh.vtu")));
  }
  EXPECT_EQ(file_text(dir / "precious.txt"), "keep me\n");
}

}  // namespace
}  // namespace rumble::testing
