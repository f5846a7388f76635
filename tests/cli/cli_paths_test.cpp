// A scenario or a command line never writes or deletes outside its results (issue 30): a results
// directory that leads out of the scenario's folder through a symbolic link is refused as one
// that leaves it with ".." is, by every command that writes there (docs/scenario.md, "The results
// directory").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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

// ---- a FEM soil's mesh.export: inside the run's results directory, only in a run

/// Bytes that are no text, to compare byte for byte.
std::string some_bytes() {
  std::string bytes;
  for (int i = 0; i < 4096; ++i) bytes.push_back(static_cast<char>((i * 7919 + 13) % 256));
  return bytes;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

/// small_fem_scenario() exporting its mesh to `path`, 2 ms long, in `dir`/s.
fs::path exporting_scenario(const fs::path& dir, const std::string& path) {
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.002;
  s["soil"]["params"]["mesh"]["export"] = path;
  fs::create_directories(dir / "s");
  return write_scenario(dir / "s", s);
}

/// What `dir` holds, every level, as paths relative to it, each with its size.
std::string listing_with_sizes(const fs::path& dir) {
  std::vector<std::string> lines;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const auto status = fs::symlink_status(e.path());
    lines.push_back(
        e.path().lexically_relative(dir).string() +
        (fs::is_regular_file(status) ? " " + std::to_string(fs::file_size(e.path())) : ""));
  }
  std::sort(lines.begin(), lines.end());
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

// mesh.export aimed at a file outside the results (beside the scenario, the scenario itself,
// anywhere by an absolute path): validate and run refuse it at /soil/params/mesh/export, and the
// file is as it was, byte for byte.
TEST(CliPaths, AMeshExportOutsideTheResultsLeavesItsTargetAsItWas) {
  const auto dir = scratch_directory("paths_export_outside");
  const std::string bytes = some_bytes();
  write_bytes(dir / "precious.bin", bytes);
  for (const std::string& target :
       {std::string("../precious.bin"), (dir / "precious.bin").string(),
        std::string("../s/scenario.json"), std::string("results/../../precious.bin")}) {
    const auto path = exporting_scenario(dir, target);
    const std::string scenario = file_text(path);
    for (const std::vector<std::string>& command :
         {std::vector<std::string>{"validate", path.string()},
          std::vector<std::string>{"run", path.string(), "--no-progress"}}) {
      const CliResult r = run_rumble(command, cache_in(dir));
      EXPECT_EQ(r.exit_code, 1) << command[0] << " " << target << ": " << r.output;
      EXPECT_THAT(r.output,
                  HasSubstr("error: /soil/params/mesh/export: is absolute or climbs out with "
                            "'..'; mesh.export is written inside the run's results directory "
                            "(outputs.directory, or --output DIR) and nowhere else: give a path "
                            "relative to it without '..', e.g. 'soil.msh', got "))
          << command[0];
      if (target.size() < 40) {  // (longer values are shortened)
        EXPECT_THAT(r.output, HasSubstr("got " + nlohmann::json(target).dump() + "\n"));
      }
      EXPECT_EQ(file_text(dir / "precious.bin"), bytes) << command[0] << " " << target;
      EXPECT_EQ(file_text(path), scenario) << command[0] << " " << target;
    }
  }
  // Set from the command line, the same.
  const auto path = exporting_scenario(dir, "soil.msh");
  const CliResult set = run_rumble({"run", path.string(), "--no-progress", "--set",
                                    "/soil/params/mesh/export=\"../../precious.bin\""},
                                   cache_in(dir));
  EXPECT_EQ(set.exit_code, 1) << set.output;
  EXPECT_THAT(set.output, HasSubstr("got \"../../precious.bin\" (set by --set)"));
  EXPECT_EQ(file_text(dir / "precious.bin"), bytes);
  EXPECT_FALSE(fs::exists(dir / "s" / "results"));
}

// Inside the results directory, nothing standing there is followed or replaced: a link on the
// way (validate passes: it writes nothing; the run stops), a link at the name (a run refuses an
// unlisted file; with --overwrite the soil refuses it), a file at the name.
TEST(CliPaths, AMeshExportNeverGoesThroughALinkInTheResults) {
  const auto dir = scratch_directory("paths_export_link");
  const std::string bytes = some_bytes();
  write_bytes(dir / "precious.bin", bytes);
  fs::create_directories(dir / "elsewhere");
  fs::create_directories(dir / "s" / "results");
  fs::create_directory_symlink(dir / "elsewhere", dir / "s" / "results" / "meshes");
  const auto through = exporting_scenario(dir, "meshes/soil.msh");
  const std::string before = listing_with_sizes(dir / "s");
  const CliResult valid = run_rumble({"validate", through.string()}, cache_in(dir));
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_EQ(listing_with_sizes(dir / "s"), before);
  const CliResult run =
      run_rumble({"run", through.string(), "--no-progress", "--overwrite"}, cache_in(dir));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output,
              HasSubstr("fem: params/mesh/export: \"meshes/soil.msh\": " +
                        (dir / "s" / "results" / "meshes").string() + " is a symbolic link (to " +
                        (dir / "elsewhere").string() +
                        "); the file is written only through real directories inside the "
                        "results directory, never through a link: move it away, or give another "
                        "path"));
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));

  fs::remove_all(dir / "s");
  fs::create_directories(dir / "s" / "results");
  fs::create_symlink(dir / "precious.bin", dir / "s" / "results" / "soil.msh");
  const auto at_name = exporting_scenario(dir, "soil.msh");
  const CliResult unlisted = run_rumble({"run", at_name.string(), "--no-progress"}, cache_in(dir));
  EXPECT_EQ(unlisted.exit_code, 1) << unlisted.output;
  EXPECT_THAT(unlisted.output, HasSubstr("that no rumble manifest lists (soil.msh)"));
  const CliResult overwrite =
      run_rumble({"run", at_name.string(), "--no-progress", "--overwrite"}, cache_in(dir));
  EXPECT_NE(overwrite.exit_code, 0) << overwrite.output;
  EXPECT_THAT(
      overwrite.output,
      HasSubstr("fem: params/mesh/export: \"soil.msh\": " +
                (dir / "s" / "results" / "soil.msh").string() +
                " is there already (a symbolic link (to " + (dir / "precious.bin").string() +
                ")); the file is written as a new one and nothing standing there is "
                "replaced (a rerun of the same scenario removes its own first): move it "
                "away, or give another path"));
  EXPECT_TRUE(fs::is_symlink(dir / "s" / "results" / "soil.msh"));
  EXPECT_EQ(file_text(dir / "precious.bin"), bytes);
}

// Where it may go, mesh.export is written by a run into its results (listed in the manifest, so
// that a rerun replaces it) and by `rumble mesh` beside mesh.vtu; `rumble validate` writes
// nothing at all.
TEST(CliPaths, AMeshExportIsWrittenByARunIntoItsResults) {
  const auto dir = scratch_directory("paths_export_run");
  const auto path = exporting_scenario(dir, "meshes/soil.msh");
  const std::string before = listing_with_sizes(dir / "s");
  const CliResult valid = run_rumble({"validate", path.string()}, cache_in(dir));
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_EQ(listing_with_sizes(dir / "s"), before);
  for (int k = 0; k < 2; ++k) {  // the rerun removes the first run's file and writes it again
    const CliResult run = run_rumble({"run", path.string(), "--no-progress"}, cache_in(dir));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_THAT(run.output, HasSubstr("fem: mesh written to " +
                                      (dir / "s" / "results" / "meshes" / "soil.msh").string()));
    EXPECT_THAT(file_text(dir / "s" / "results" / "meshes" / "soil.msh"), HasSubstr("$MeshFormat"));
  }
  const auto manifest = read_json(dir / "s" / "results" / ".rumble-manifest.json");
  EXPECT_THAT(manifest["files"].dump(), HasSubstr("\"meshes/soil.msh\""));
  EXPECT_THAT(manifest["directories"].dump(), HasSubstr("\"meshes\""));

  const CliResult mesh =
      run_rumble({"mesh", path.string(), "--output", (dir / "m").string()}, cache_in(dir));
  ASSERT_EQ(mesh.exit_code, 0) << mesh.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "m" / "meshes" / "soil.msh"));
  EXPECT_TRUE(fs::is_regular_file(dir / "m" / "mesh.vtu"));
  const CliResult again =
      run_rumble({"mesh", path.string(), "--output", (dir / "m").string()}, cache_in(dir));
  EXPECT_EQ(again.exit_code, 3) << again.output;
  EXPECT_THAT(again.output, HasSubstr(" is there already (a file)"));
}

}  // namespace
}  // namespace rumble::testing
