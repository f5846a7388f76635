// `rumble post` and the post-processing `rumble run` does after a run with receivers: the
// indicators land in RESULTS_DIR/post and in the results manifest (so a rerun replaces them), the
// command's options reach them, and a directory without a run, or a bad option, is refused with
// what, where and the fix. The numbers themselves are checked in tests/post.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

/// A small FEM run with receivers at 2.5 m and 5 m, into dir/results; returns that directory
/// (and the run's output in `output` when given).
std::filesystem::path run_with_receivers(const std::filesystem::path& dir,
                                         std::string* output = nullptr) {
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.03;
  s["outputs"]["receivers"] = {2.5, 5.0};
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  ::unsetenv("RUMBLE_MESH_CACHE");
  if (output != nullptr) *output = r.output;
  return dir / "results";
}

TEST(CliPost, ARunWritesTheIndicatorsAndPostRewritesThemWithItsOptions) {
  const auto dir = scratch_directory("post_after_run");
  const auto results = run_with_receivers(dir);
  for (const char* f : {"ppv.csv", "spectra.csv", "third_octave.csv", "post.json"})
    EXPECT_TRUE(std::filesystem::exists(results / "post" / f)) << f;
  EXPECT_THAT(file_text(results / ".rumble-manifest.json"), HasSubstr("post/ppv.csv"));
  EXPECT_THAT(file_text(results / "post" / "third_octave.csv"), HasSubstr("dB re 1e-09 m/s"));

  const CliResult post = run_rumble({"post", results.string(), "--reference", "vdb"});
  ASSERT_EQ(post.exit_code, 0) << post.output;
  EXPECT_THAT(post.output, HasSubstr("vibration indicators in"));
  EXPECT_THAT(file_text(results / "post" / "third_octave.csv"), HasSubstr("dB re 2.54e-08 m/s"));

  // The scenario's rerun replaces its results, post/ included, without --overwrite.
  const CliResult rerun =
      run_rumble({"run", (dir / "scenario.json").string(), "--no-progress", "--no-plots"});
  EXPECT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_THAT(file_text(results / "post" / "third_octave.csv"), HasSubstr("dB re 1e-09 m/s"));
}

// A FEM soil says the band its mesh carries to each receiver (ABI 1.3): the run logs it,
// summary.json keeps it per receiver with the rule, it falls with distance, and post/ gives the
// share of energy above it and the PPV within it next to the raw PPV. The numbers themselves:
// tests/fem/resolved_band_test.cpp, tests/post/resolved_band_test.cpp.
TEST(CliPost, EachReceiverSaysTheBandItsMeshResolvesAndTheIndicatorsWithinIt) {
  const auto dir = scratch_directory("post_resolved_band");
  std::string output;
  run_with_receivers(dir, &output);
  EXPECT_THAT(output, HasSubstr("receivers resolved to: d=2.5 m "));
  const nlohmann::json summary = read_json(dir / "results" / "summary.json");
  EXPECT_THAT(summary.at("resolved_band_rule").get<std::string>(),
              HasSubstr("n = 10 linear elements per Rayleigh wavelength"));
  const double near = summary.at("ppv")[0].at("resolved_f_hz").get<double>();
  const double far = summary.at("ppv")[1].at("resolved_f_hz").get<double>();
  // 40 Hz within 1.5 m of the track by the mesh's rule; coarser further out.
  EXPECT_GT(near, 15.0);
  EXPECT_LT(near, 60.0);
  EXPECT_LT(far, near);
  const nlohmann::json post = read_json(dir / "results" / "post" / "post.json");
  for (const nlohmann::json& rx : post.at("receivers")) {
    const nlohmann::json& band = rx.at("resolved_band");
    EXPECT_GT(band.at("f_hz").get<double>(), 0.0);
    EXPECT_GE(band.at("energy_z_above").get<double>(), 0.0);
    EXPECT_LE(band.at("energy_z_above").get<double>(), 1.0);
    EXPECT_GT(band.at("ppv_z_m_s").get<double>(), 0.0);
  }
  EXPECT_THAT(file_text(dir / "results" / "post" / "ppv.csv"), HasSubstr("PPV_z resolved [m/s]"));
}

// The scenario's outputs.post chooses the run's indicators; `rumble post` keeps them unless its
// options say otherwise; a bad value is refused at validation with its pointer.
TEST(CliPost, TheScenarioChoosesTheIndicatorsAndPostKeepsThem) {
  const auto dir = scratch_directory("post_from_scenario");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.02;
  s["outputs"]["receivers"] = {2.5, 5.0};
  s["outputs"]["post"] = {{"cwt_distances", {5.0}}, {"f_max", 30.0}, {"reference", "vdb"}};
  const auto file = write_scenario(dir, s).string();
  const CliResult r = run_rumble({"run", file, "--no-progress"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto post = dir / "results" / "post";
  const auto options = [&] { return read_json(post / "post.json")["options"]; };
  EXPECT_EQ(options()["cwt_f_max_hz"], 30.0);
  EXPECT_EQ(options()["cwt_distances_m"], nlohmann::json({5.0}));
  EXPECT_TRUE(std::filesystem::exists(post / "cwt_d=5_m.csv"));
  EXPECT_FALSE(std::filesystem::exists(post / "cwt_d=2.5_m.csv"));
  EXPECT_THAT(file_text(post / "third_octave.csv"), HasSubstr("dB re 2.54e-08 m/s"));

  const CliResult again = run_rumble({"post", (dir / "results").string(), "--f-max", "50"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(options()["cwt_f_max_hz"], 50.0);                      // the option
  EXPECT_EQ(options()["cwt_distances_m"], nlohmann::json({5.0}));  // the scenario's
  EXPECT_THAT(file_text(post / "third_octave.csv"), HasSubstr("dB re 2.54e-08 m/s"));

  s["outputs"]["post"]["f_max"] = 0.0;
  const CliResult bad = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_THAT(bad.output, HasSubstr("/outputs/post/f_max"));
}

TEST(CliPost, RefusesADirectoryNoRunWrote) {
  const auto dir = scratch_directory("post_no_run");
  const CliResult r = run_rumble({"post", dir.string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("holds no results of a rumble run"));
  EXPECT_THAT(r.output, HasSubstr("run the scenario into it first"));
  std::ofstream(dir / ".rumble-manifest.json") << "{not json";
  const CliResult broken = run_rumble({"post", dir.string()});
  EXPECT_EQ(broken.exit_code, 1) << broken.output;
  EXPECT_THAT(broken.output, HasSubstr(".rumble-manifest.json cannot be used"));
  const CliResult missing = run_rumble({"post", (dir / "nothere").string()});
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_THAT(missing.output, HasSubstr("is not a directory"));
}

// Any directory holding a receivers.csv can be post-processed (issue #29): without a manifest
// post/ is written new and listed in one, so post runs again over it; a post/ that nothing says
// rumble wrote is never replaced.
TEST(CliPost, ADirectoryWithReceiversButNoManifestIsPostProcessedWithoutReplacingAnything) {
  const auto dir = scratch_directory("post_no_manifest");
  const auto results = run_with_receivers(dir);
  const auto copy = dir / "copied";
  std::filesystem::create_directories(copy);
  std::filesystem::copy_file(results / "receivers.csv", copy / "receivers.csv");
  const CliResult first = run_rumble({"post", copy.string()});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(std::filesystem::exists(copy / "post" / "ppv.csv"));
  EXPECT_THAT(file_text(copy / ".rumble-manifest.json"), HasSubstr("post/ppv.csv"));
  const CliResult again = run_rumble({"post", copy.string(), "--reference", "vdb"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_THAT(file_text(copy / "post" / "third_octave.csv"), HasSubstr("dB re 2.54e-08 m/s"));

  const auto theirs = dir / "theirs";
  std::filesystem::create_directories(theirs / "post");
  std::filesystem::copy_file(results / "receivers.csv", theirs / "receivers.csv");
  std::ofstream(theirs / "post" / "ppv.csv") << "their own\n";
  const CliResult refused = run_rumble({"post", theirs.string()});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("holds receivers.csv but no .rumble-manifest.json"));
  EXPECT_THAT(refused.output, HasSubstr("move or remove it, then run rumble post again"));
  EXPECT_EQ(file_text(theirs / "post" / "ppv.csv"), "their own\n");
}

// A run stopped as diverged keeps what it recorded, and its receivers are post-processed up to
// where it got: the PPV of a diverging run is how the seed paper shows the divergence (its Figure
// 4), and the study report draws such a run dashed. Here a 5 mm rail dip under the starting wheel
// and a divergence bound of 2.01 x the static settlement stop the run at its impact.
TEST(CliPost, ADivergedRunIsPostProcessedUpToWhereItGot) {
  const auto dir = scratch_directory("post_diverged");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.03;
  s["track"]["unevenness"] = {{"type", "dip"}, {"position", 3.2}, {"length", 0.3}, {"depth", 5e-3}};
  s["coupling"]["divergence"] = {{"displacement_factor", 2.01}};
  s["outputs"]["receivers"] = {2.5, 5.0};
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("simulation diverged at t = "));
  EXPECT_EQ(read_json(dir / "results" / "summary.json")["status"], "failed");
  EXPECT_TRUE(std::filesystem::exists(dir / "results" / "post" / "ppv.csv"));
  EXPECT_THAT(file_text(dir / "results" / "post" / "ppv.csv"), HasSubstr("d=2.5 m"));
}

// What post reads is a run's files: a FIFO in their place waited for a writer for ever and
// /dev/zero was read without end (issue #30 item 3). Each is refused before it is opened, named
// with what it is, and a receivers.csv larger than post reads whole (a sparse file of 5 GiB)
// with the bound.
TEST(CliPost, InputsThatAreNotRegularFilesOfBoundedSizeAreRefusedUnread) {
  const auto dir = scratch_directory("post_hostile_inputs");
  const auto results = run_with_receivers(dir);
  namespace fs = std::filesystem;
  struct Case {
    const char* file;
    const char* kind;  // "fifo", "device" or "huge"
    std::string says;
  };
  for (const Case& c : std::vector<Case>{
           Case{"receivers.csv", "fifo",
                "receivers.csv is a FIFO (named pipe), not a regular file: rumble post reads the "
                "CSV files a run wrote, regular files of at most 4 GiB"},
           Case{"receivers.csv", "device", "receivers.csv is a device, not a regular file"},
           Case{"receivers.csv", "huge",
                "receivers.csv is 5.37e+09 bytes, more than the "
                "4.29e+09 that rumble reads of it"},
           Case{"summary.json", "fifo",
                "summary.json in '" + results.string() +
                    "' is a FIFO (named pipe), not a regular file: rumble post reads the "
                    "summary.json a run wrote, a regular file of at most 64 MiB; rerun the "
                    "scenario into the directory"},
           Case{"summary.json", "device", "summary.json in '"},
       }) {
    const fs::path file = results / c.file, kept = results / "kept";
    fs::rename(file, kept);
    const std::string kind = c.kind;
    if (kind == "fifo") {
      ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
    } else if (kind == "device") {
      fs::create_symlink("/dev/zero", file);
    } else {
      std::ofstream(file).close();
      fs::resize_file(file, std::uintmax_t{5} << 30);  // sparse: no disk spent
    }
    const CliResult r = run_rumble({"post", results.string()});
    EXPECT_EQ(r.exit_code, 1) << c.file << " " << kind << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.says)) << c.file << " " << kind;
    fs::remove(file);
    fs::rename(kept, file);
  }
  const CliResult again = run_rumble({"post", results.string()});
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

TEST(CliPost, ARunWithoutReceiversSaysSo) {
  const auto dir = scratch_directory("post_no_receivers");
  const CliResult run =
      run_rumble({"run", write_scenario(dir, small_scenario()).string(), "--no-progress"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "results" / "post"));
  const CliResult r = run_rumble({"post", (dir / "results").string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("receivers.csv"));
}

TEST(CliPost, BadOptionsNameTheOptionAndTheFix) {
  const auto dir = scratch_directory("post_bad_options");
  const CliResult r = run_rumble({"post", dir.string(), "--cwt-distances", "2.5,far"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("'far' is not a distance in metres"));
  const CliResult ref = run_rumble({"post", dir.string(), "--reference", "dbv"});
  EXPECT_EQ(ref.exit_code, 1) << ref.output;
  EXPECT_THAT(ref.output, HasSubstr("vdb"));
}

}  // namespace
}  // namespace rumble::testing
