// Issue #8 as a careless or hostile user meets it at the command line: help everywhere, JSON that
// is only JSON, a bad plugin path or a FIFO that neither stops nor hangs the CLI, runs too large
// for the machine refused before they start, counts that are counts, duplicate keys refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

const char* const kCommands[] = {"run",       "validate", "study",      "plugins",
                                 "schema",    "mesh",     "soil-frf",   "calibrate",
                                 "stability", "post",     "new-plugin", "help"};

TEST(CliReliability, EveryCommandHasHelpWithDefaults) {
  for (const char* command : kCommands) {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"help", command}, {command, "--help"}, {command, "x", "-h"}}) {
      const CliResult r = run_rumble(args);
      EXPECT_EQ(r.exit_code, 0) << command << ": " << r.output;
      EXPECT_THAT(r.output, HasSubstr(std::string("usage: rumble ") + command)) << command;
    }
  }
  EXPECT_THAT(run_rumble({"help", "run"}).output, HasSubstr("--yes"));
  EXPECT_THAT(run_rumble({"soil-frf", "--help"}).output, HasSubstr("(default: 100)"));
  const CliResult overview = run_rumble({"help"});
  EXPECT_EQ(overview.exit_code, 0);
  EXPECT_THAT(overview.output, HasSubstr("commands:"));
  const CliResult unknown = run_rumble({"help", "rnu"});
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_THAT(unknown.output, HasSubstr("help: unknown command 'rnu'"));
}

TEST(CliReliability, SchemaListsTypesAndItsJsonIsOnlyJson) {
  const CliResult list = run_rumble({"schema"});
  EXPECT_EQ(list.exit_code, 0) << list.output;
  EXPECT_THAT(list.output, HasSubstr("vehicle: "));
  EXPECT_THAT(list.output, HasSubstr("single_wheel"));
  EXPECT_THAT(list.output, HasSubstr("soil: "));
  const CliResult j = run_rumble({"schema", "single_wheel", "--json"});
  EXPECT_EQ(j.exit_code, 0) << j.output;
  ASSERT_TRUE(nlohmann::json::accept(j.output)) << j.output;
  EXPECT_TRUE(nlohmann::json::parse(j.output).contains("properties"));
}

TEST(CliReliability, ValidateJsonReportsPluginLoadErrorsAsJson) {
  nlohmann::json s = small_scenario();
  s["plugins"] = {"missing.so"};
  const auto path = write_scenario(scratch_directory("validate_json_load_error"), s);
  const CliResult r = run_rumble({"validate", path.string(), "--format", "json"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  ASSERT_TRUE(nlohmann::json::accept(r.output)) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["errors"], 1);
  EXPECT_THAT(j["diagnostics"][0]["message"].get<std::string>(), HasSubstr("/plugins/0: plugin '"));
  EXPECT_THAT(j["diagnostics"][0]["message"].get<std::string>(), HasSubstr("file not found"));
}

// dlopen on a FIFO waits for a writer: validate and run hung.
TEST(CliReliability, FifoInPluginsIsRefusedNotWaitedOn) {
  const auto dir = scratch_directory("fifo_plugin");
  ASSERT_EQ(mkfifo((dir / "pipe.so").c_str(), 0600), 0);
  nlohmann::json s = small_scenario();
  s["plugins"] = {"pipe.so"};
  const CliResult r = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("/plugins/0: plugin '"));
  EXPECT_THAT(r.output,
              HasSubstr("': a FIFO (named pipe), not a regular file; name a shared library"));
}

// One bad library or missing directory in RUMBLE_PLUGIN_PATH made every command fail.
TEST(CliReliability, BadPluginPathEntriesAreReportedAndSkipped) {
  const auto dir = scratch_directory("bad_plugin_path");
  std::ofstream(dir / "broken.so") << std::string(200, '#') << "\nnot a library\n";
  const std::string path = (dir / "broken.so").string() + ":" + (dir / "missing_dir").string();
  ASSERT_EQ(setenv("RUMBLE_PLUGIN_PATH", path.c_str(), 1), 0);
  const CliResult plugins = run_rumble({"plugins"});
  const CliResult validate =
      run_rumble({"validate", write_scenario(dir, small_scenario()).string()});
  unsetenv("RUMBLE_PLUGIN_PATH");
  EXPECT_EQ(plugins.exit_code, 0) << plugins.output;
  EXPECT_THAT(plugins.output, HasSubstr("soil winkler"));
  EXPECT_THAT(plugins.output, HasSubstr("(from engine plugin directory)"));
  EXPECT_THAT(plugins.output, HasSubstr("not loaded (skipped; the plugins above are usable):"));
  EXPECT_THAT(plugins.output, HasSubstr("broken.so  (from RUMBLE_PLUGIN_PATH): plugin '"));
  EXPECT_THAT(plugins.output,
              HasSubstr("RUMBLE_PLUGIN_PATH entry '" + (dir / "missing_dir").string() +
                        "': no such file or directory"));
  EXPECT_EQ(validate.exit_code, 0) << validate.output;
  EXPECT_THAT(validate.output, HasSubstr("skipped, the other plugins are loaded"));
}

// time.macro_step 1e-12 validated and then wrote about 1 GB a minute toward 5e10 steps.
TEST(CliReliability, RunsBeyondTheSizeLimitsAreRefusedUnlessConfirmed) {
  // The longest run at the shortest macro step the schema allows (docs/scenario.md, "Limits"):
  // an hour in steps of 1e-7 s, the vehicle standing so that it stays on the rail.
  nlohmann::json s = small_scenario();
  s["time"] = {{"end", 3600.0}, {"macro_step", 1e-7}};
  s["vehicles"][0]["speed"] = 0.0;
  const auto dir = scratch_directory("run_size");
  const auto path = write_scenario(dir, s).string();
  const CliResult r = run_rumble({"validate", path});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /time/macro_step: the run takes 3.6e+10 macro steps "
                                  "(time.end 3600 s / macro_step 1e-07 s), more than the limit "
                                  "of 1e+07"));
  EXPECT_THAT(r.output, HasSubstr("if this run is meant, confirm it with --yes"));
  EXPECT_THAT(r.output, HasSubstr("error: /outputs/every: the time histories would take about "));
  const CliResult run = run_rumble({"run", path, "--no-progress"});
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_FALSE(fs::exists(dir / "results"));
  const CliResult confirmed = run_rumble({"validate", path, "--yes"});
  EXPECT_EQ(confirmed.exit_code, 0) << confirmed.output;
  // Confirmed, the run is held against what this machine has free (issue #30 item 2): its
  // histories (3.6e10 records: 268 GiB of memory, 46 TiB on disk) fit neither, and --yes
  // does not waive that. Before, it began and wrote until the disk was full.
  const CliResult run_confirmed = run_rumble({"run", path, "--no-progress", "--yes"});
  EXPECT_EQ(run_confirmed.exit_code, 1) << run_confirmed.output;
  EXPECT_THAT(run_confirmed.output,
              HasSubstr("error: /time/end: the run needs about 268 GiB of memory (22 KiB for the "
                        "static state of 20 sleepers, 268 GiB for its histories), more than the "));
  EXPECT_THAT(run_confirmed.output,
              HasSubstr("this machine has available now (MemAvailable, or the cgroup's limit); "
                        "--yes does not waive this"));
  EXPECT_THAT(run_confirmed.output, HasSubstr("error: /outputs/every: the time histories would "
                                              "take at least "));
  EXPECT_THAT(run_confirmed.output, HasSubstr(" free under " + (dir / "results").string()));
  EXPECT_FALSE(fs::exists(dir / "results"));
}

// receivers.csv grew about 30 times past the size estimate (issue #30 item 2): the soil samples
// its receivers inside its own steps, six values each. Validation now counts six values a
// receiver at least once a macro step (or every receiver_interval), and the run projects the
// file from the soil's rate at its first step: 100 receivers over 400 s of a small FEM soil
// (5000 samples a second) would write about 19 GiB, and the run stops at once with the
// projection and the fix.
TEST(CliReliability, ReceiversProjectedBeyondTheLimitStopTheRunAtItsFirstStep) {
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 400.0;         // s
  s["vehicles"][0]["speed"] = 0.0;  // at rest: the rail is short
  s["outputs"]["receivers"] = nlohmann::json::array();
  for (int k = 0; k < 100; ++k) s["outputs"]["receivers"].push_back(1.0 + 0.04 * k);  // m
  const auto dir = scratch_directory("receivers_size");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const auto path = write_scenario(dir, s).string();
  const CliResult run = run_rumble({"run", path, "--no-progress"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_THAT(run.output, HasSubstr("/outputs/receiver_interval: receivers.csv would take about "));
  EXPECT_THAT(run.output, HasSubstr("GiB limit on time histories; set outputs.receiver_interval"));
  EXPECT_LT(csv_rows(dir / "results" / "contact.csv"), 3u);  // stopped at its first step
  EXPECT_LT(fs::file_size(dir / "results" / "receivers.csv"), 1u << 20);
}

// Field snapshots had no size limit (16 GB written): the first snapshot's size times the
// snapshots to come is checked at once (here 9901 snapshots of a small FEM soil meshed for
// 120 Hz, within validation's count limit of 1e4, each about 1.4 MiB).
TEST(CliReliability, FieldsProjectedBeyondTheLimitStopTheRunAtTheFirstSnapshot) {
  nlohmann::json s = small_fem_scenario();
  s["soil"]["params"]["mesh"]["f_max"] = 120.0;   // Hz
  s["time"]["end"] = 99.0;                        // s
  s["vehicles"][0]["speed"] = 0.0;                // at rest: the rail is short
  s["outputs"]["fields"] = {{"interval", 1e-2}};  // s
  const auto dir = scratch_directory("fields_size");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const CliResult run = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_THAT(run.output, HasSubstr("/outputs/fields/interval: the field snapshots would take "
                                    "about "));
  EXPECT_THAT(run.output, HasSubstr("(9.9e+03 snapshots of "));
  EXPECT_EQ(
      std::distance(fs::directory_iterator(dir / "results" / "fields"), fs::directory_iterator{}),
      1);
}

// sleepers.count 1e7 died of std::bad_alloc, 2^63-1 gave a message about the vehicle's start, and
// a hint read "use at least -2147483647 sleepers".
// The schema's maximum of 1e5 sleepers ended in std::bad_alloc in the statics, which hold dense
// n x n matrices (56 n^2 bytes: 560 GB there); 5e3-1e4 sleepers took minutes and 5.5 GB
// (issue #30 item 2). Validation now estimates it: at the maximum the run is refused with the
// estimate and the count that fits; 1e4 sleepers (5.6 GB) is within the limit.
TEST(CliReliability, TheStaticsOfTheLargestTrackAreEstimatedBeforeTheyAreSpent) {
  for (const int count : {100000, 10000}) {
    nlohmann::json s = small_scenario();
    s["track"]["sleepers"]["count"] = count;
    const auto dir = scratch_directory("statics_" + std::to_string(count));
    const CliResult r = run_rumble({"validate", write_scenario(dir, s).string()});
    if (count == 10000) {
      EXPECT_EQ(r.exit_code, 0) << r.output;
      continue;
    }
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("error: /track/sleepers/count: the static state of 100000 "
                                    "sleepers needs about 522 GiB of memory (dense 100000 x "
                                    "100000 matrices of the track/soil interface), more than the "
                                    "limit of 8.0 GiB"));
    EXPECT_THAT(r.output, HasSubstr("use at most 12385 sleepers"));
  }
  // Confirmed with --yes, the maximum is held against the memory this machine has: refused at
  // once with what fits, where it died of std::bad_alloc after allocating (issue #30 item 2).
  nlohmann::json s = small_scenario();
  s["track"]["sleepers"]["count"] = 100000;
  const auto dir = scratch_directory("statics_confirmed");
  const CliResult r =
      run_rumble({"run", write_scenario(dir, s).string(), "--no-progress", "--yes"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /track/sleepers/count: the run needs about 522 GiB of "
                                  "memory (522 GiB for the static state of 100000 sleepers"));
  EXPECT_THAT(r.output, HasSubstr("hint: use at most "));
  EXPECT_FALSE(fs::exists(dir / "results"));
}

TEST(CliReliability, SleeperCountHasAnUpperBoundAndHintsDoNotOverflow) {
  for (const char* count : {"10000000", "9223372036854775807"}) {
    nlohmann::json s = small_scenario();
    const auto dir = scratch_directory(std::string("sleepers_") + count);
    std::string text = s.dump(2);
    const std::string key = "\"count\": 20";
    text.replace(text.find(key), key.size(), std::string("\"count\": ") + count);
    std::ofstream(dir / "scenario.json") << text;
    const CliResult r = run_rumble({"validate", (dir / "scenario.json").string()});
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("/track/sleepers/count: must be in [3, 100000], got " +
                                    std::string(count)))
        << count;
  }
  nlohmann::json s = small_scenario();
  s["time"]["end"] = 3600.0;  // the longest run the schema allows
  s["time"]["macro_step"] = 1e-1;
  const CliResult far =
      run_rumble({"validate", write_scenario(scratch_directory("far"), s).string()});
  EXPECT_EQ(far.exit_code, 1) << far.output;
  EXPECT_THAT(far.output, HasSubstr("hint: lower time.end or the speed (the rail would need "
                                    "120008 sleepers, more than the 100000 allowed)"));
  EXPECT_THAT(far.output, Not(HasSubstr("-2147483647")));
}

TEST(CliReliability, ValidateWithoutLoadingPlugins) {
  nlohmann::json s = small_scenario();
  s["plugins"] = {"not_built_yet.so"};
  s["soil"]["type"] = "my_soil";
  const auto path = write_scenario(scratch_directory("validate_no_load"), s).string();
  const CliResult r = run_rumble({"validate", path, "--no-load"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("valid (--no-load: component types, params and plugins not "
                                  "checked)"));
  s["time"]["end"] = -1;
  const auto bad = write_scenario(scratch_directory("validate_no_load_bad"), s).string();
  const CliResult b = run_rumble({"validate", bad, "--no-load"});
  EXPECT_EQ(b.exit_code, 1) << b.output;
  EXPECT_THAT(b.output, HasSubstr("/time/end: must be in [1e-06, 3600], got -1"));
}

TEST(CliReliability, DuplicateKeysAreRefused) {
  const auto dir = scratch_directory("duplicate_keys");
  std::string text = small_scenario().dump(2);
  const std::string key = "\"end\": 0.05";
  text.replace(text.find(key), key.size(), "\"end\": 0.05, \"end\": 5");
  std::ofstream(dir / "scenario.json") << text;
  const CliResult r = run_rumble({"validate", (dir / "scenario.json").string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /time/end: duplicate key \"end\" (first at line "));
}

TEST(CliReliability, SoilFrfCountsAreWholeNumbersAndItsOutputIsADirectory) {
  const auto dir = scratch_directory("soil_frf_arguments");
  const auto path = write_scenario(dir, small_scenario()).string();
  const CliResult half = run_rumble({"soil-frf", path, "--points", "2.5", "--no-plot"});
  EXPECT_EQ(half.exit_code, 1);
  EXPECT_THAT(half.output, HasSubstr("--points=2.5 is not a whole number; give a whole number "
                                     "from 2 to 100000"));
  const CliResult huge = run_rumble({"soil-frf", path, "--points", "1e9", "--no-plot"});
  EXPECT_EQ(huge.exit_code, 1);
  EXPECT_THAT(huge.output, HasSubstr("--points=1e9 is too large; give a whole number from 2 to "
                                     "100000"));
  const CliResult file =
      run_rumble({"soil-frf", path, "--output", (dir / "x.csv").string(), "--no-plot"});
  EXPECT_EQ(file.exit_code, 1);
  EXPECT_THAT(file.output, HasSubstr("x.csv names a file; this command writes one CSV per "
                                     "scenario into the directory --output names, e.g. --output "));
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
  // The same for every --output that names a directory.
  for (const char* command : {"run", "mesh"}) {
    const CliResult r = run_rumble({command, path, "--output", (dir / "out.json").string()});
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_THAT(r.output, HasSubstr("out.json names a file; this command writes ")) << command;
    EXPECT_FALSE(fs::exists(dir / "out.json")) << command;
  }
}

// soil-frf writes into a results directory like run's: locked, with a manifest, so a rerun
// replaces its own files.
TEST(CliReliability, SoilFrfOwnsItsDirectory) {
  const auto dir = scratch_directory("soil_frf_manifest");
  const auto path = write_scenario(dir, small_scenario()).string();
  for (int i = 0; i < 2; ++i) {
    const CliResult r = run_rumble({"soil-frf", path, "--no-plot"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto out = dir / "results" / "soil_frf";
  const nlohmann::json manifest = read_json(out / ".rumble-manifest.json");
  EXPECT_THAT(manifest.dump(), HasSubstr("scenario_winkler.csv"));
  EXPECT_TRUE(fs::exists(out / "scenario_winkler.csv"));
}

// An mbs vehicle's definition file of /dev/zero grew to 4 GB; at validate time now, at the
// vehicle's params, with the value and the fix.
TEST(CliReliability, MbsDefinitionFileMustBeARegularFile) {
  nlohmann::json s = small_scenario();
  s["vehicles"][0]["type"] = "mbs";
  s["vehicles"][0]["params"] = {{"file", "/dev/zero"}};
  const CliResult r =
      run_rumble({"validate", write_scenario(scratch_directory("mbs_dev_zero"), s).string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /vehicles/0/params/file: "));  // the key it names
  EXPECT_THAT(r.output, HasSubstr("params/file: \"/dev/zero\" is not a regular file (a directory, "
                                  "device or pipe), got \"/dev/zero\"; name a vehicle definition "
                                  "file (JSON)"));
}

// A results directory that cannot be made was found only when the run began.
TEST(CliReliability, ResultsDirectoryThatIsAFileIsAValidateError) {
  const auto dir = scratch_directory("results_is_a_file");
  std::ofstream(dir / "results") << "not a directory\n";
  const CliResult r = run_rumble({"validate", write_scenario(dir, small_scenario()).string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /outputs/directory: \"" + (dir / "results").string() +
                                  "\" is a file, not a directory"));
  nlohmann::json s = small_scenario();
  s["outputs"]["directory"] = "results/run1";
  const CliResult below = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_EQ(below.exit_code, 1) << below.output;
  EXPECT_THAT(below.output,
              HasSubstr("cannot create \"" + (dir / "results" / "run1").string() + "\": \"" +
                        (dir / "results").string() + "\" is a file, not a directory"));
}

}  // namespace
}  // namespace rumble::testing
