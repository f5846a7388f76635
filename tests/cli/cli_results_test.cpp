// What a run does with its results directory (issue #8): one run at a time (a lock naming the
// holder), a rerun of the same scenario file replaces exactly what the last one listed (a
// manifest) and anything else needs --overwrite, nothing is written outside the scenario's folder
// unless the command line says so, no write goes through a symbolic link, and summary.json's
// heartbeat tells a run that died from one that is alive.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <thread>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

/// small_scenario() for 100000 macro steps: several seconds of wall time.
nlohmann::json long_scenario() {
  nlohmann::json s = small_scenario();
  s["time"] = {{"end", 2.0}, {"macro_step", 2e-5}};
  s["vehicles"][0]["speed"] = 5.0;
  s["track"]["sleepers"]["count"] = 40;
  return s;
}

/// Waits (at most 60 s) until `ready` holds; false when it never did.
template <class F>
bool wait_for(F ready) {
  for (int i = 0; i < 1200; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// summary.json as it stands, or null while there is none.
nlohmann::json summary_now(const fs::path& results) {
  try {
    return read_json(results / "summary.json");
  } catch (const std::exception&) {
    return nullptr;
  }
}

double unix_time_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

// ---- one run at a time

TEST(CliResults, ASecondRunIntoTheSameDirectoryStopsAtOnceNamingTheFirst) {
  const auto dir = scratch_directory("results_lock");
  const auto path = write_scenario(dir, long_scenario());
  const auto results = dir / "results";
  const pid_t first = start_rumble({"run", path.string(), "--no-progress"});
  ASSERT_TRUE(wait_for([&] { return csv_rows(results / "contact.csv") >= 5; }));
  const auto started = std::chrono::steady_clock::now();
  const CliResult second = run_rumble({"run", path.string(), "--no-progress"});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  kill(first, SIGINT);
  EXPECT_EQ(wait_rumble(first), 3);
  EXPECT_EQ(second.exit_code, 3) << second.output;
  EXPECT_THAT(second.output,
              HasSubstr("results directory " + results.string() +
                        " is in use by another rumble run (process id " + std::to_string(first) +
                        ", lock file " + (results / ".rumble.lock").string() + ")"));
  EXPECT_THAT(second.output, HasSubstr("Wait for that run to end, or give this one another "
                                       "directory: /outputs/directory, or --output DIR"));
  EXPECT_LT(seconds, 30.0);
  // The first run's results, whole: its summary, one row per macro step and no more.
  const auto summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["time"]["macro_steps"].get<std::size_t>() + 1,
            csv_rows(results / "contact.csv"));
}

// The kernel drops the lock with the process, however it ends.
TEST(CliResults, TheLockDiesWithItsProcess) {
  const auto dir = scratch_directory("results_lock_killed");
  const auto path = write_scenario(dir, long_scenario());
  const pid_t run = start_rumble({"run", path.string(), "--no-progress"});
  ASSERT_TRUE(wait_for([&] { return csv_rows(dir / "results" / "contact.csv") >= 5; }));
  kill(run, SIGKILL);  // as a crash: nothing of rumble's runs after this
  EXPECT_EQ(wait_rumble(run), 128 + SIGKILL);
  nlohmann::json s = long_scenario();
  s["time"]["end"] = 0.002;
  write_scenario(dir, s);
  const CliResult again = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_json(dir / "results" / "summary.json")["status"], "completed");
}

// ---- the heartbeat

// A killed run cannot say so: its summary stays "running", with a heartbeat that has stopped (the
// last macro step it finished, and when) and the process that wrote it.
TEST(CliResults, ARunThatDiedSaysRunningWithAHeartbeatThatStopped) {
  const auto dir = scratch_directory("results_heartbeat");
  const auto path = write_scenario(dir, long_scenario());
  const auto results = dir / "results";
  const double before = unix_time_now();
  const pid_t run = start_rumble({"run", path.string(), "--no-progress"});
  ASSERT_TRUE(wait_for([&] {
    const auto s = summary_now(results);
    return s.is_object() && s["heartbeat"]["macro_steps"].get<std::size_t>() > 0;
  }));
  kill(run, SIGKILL);
  EXPECT_EQ(wait_rumble(run), 128 + SIGKILL);
  const double after = unix_time_now();
  const auto summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "running");
  EXPECT_EQ(summary["process"]["pid"], run);
  EXPECT_FALSE(summary["process"]["host"].get<std::string>().empty());
  const auto& beat = summary["heartbeat"];
  const auto steps = beat["macro_steps"].get<std::size_t>();
  EXPECT_NEAR(beat["t_s"].get<double>(), 2e-5 * static_cast<double>(steps), 1e-9);
  EXPECT_GE(beat["unix_time_s"].get<double>(), before - 1.0);
  EXPECT_LE(beat["unix_time_s"].get<double>(), after + 1.0);
  EXPECT_TRUE(std::regex_match(beat["utc"].get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << beat["utc"];
  // A run that ended says so, with its last heartbeat.
  nlohmann::json s = long_scenario();
  s["time"]["end"] = 0.002;
  write_scenario(dir, s);
  const CliResult again = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(again.exit_code, 0) << again.output;
  const auto done = read_json(results / "summary.json");
  EXPECT_EQ(done["status"], "completed");
  EXPECT_EQ(done["heartbeat"]["macro_steps"], 100);
  EXPECT_NEAR(done["heartbeat"]["t_s"].get<double>(), 0.002, 1e-12);
}

// The next look at a dead run's directory says so (issue #30 item 4): whoever takes its free
// lock (here `rumble post`) rewrites the summary as "died" with what the last heartbeat says, and
// warns; the results stay.
TEST(CliResults, TheNextLookAtADeadRunSaysItDied) {
  const auto dir = scratch_directory("results_died");
  const auto results = dir / "results";
  const pid_t run =
      start_rumble({"run", write_scenario(dir, long_scenario()).string(), "--no-progress"});
  ASSERT_TRUE(wait_for([&] {
    const auto s = summary_now(results);
    return s.is_object() && s["heartbeat"]["macro_steps"].get<std::size_t>() > 0;
  }));
  kill(run, SIGKILL);
  EXPECT_EQ(wait_rumble(run), 128 + SIGKILL);
  EXPECT_EQ(read_json(results / "summary.json")["status"], "running");
  const CliResult post = run_rumble({"post", results.string()});
  EXPECT_THAT(post.output, HasSubstr("the run died without a word (a kill -9, a crash it could "
                                     "not record, or the machine stopping): it had reached t = "));
  const auto summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "died");
  EXPECT_THAT(summary["message"].get<std::string>(),
              HasSubstr("process " + std::to_string(run) + " on "));
  EXPECT_TRUE(std::filesystem::exists(results / "contact.csv"));
  // Settled once: the next look finds nothing to say.
  EXPECT_THAT(run_rumble({"post", results.string()}).output, Not(HasSubstr("died without")));
}

// ---- what a rerun replaces

TEST(CliResults, ARunListsWhatItWroteInAManifest) {
  const auto dir = scratch_directory("results_manifest");
  const auto path = write_scenario(dir, small_scenario());
  const CliResult r = run_rumble({"run", path.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto manifest = read_json(dir / "results" / ".rumble-manifest.json");
  EXPECT_EQ(manifest["scenario_file"], fs::canonical(path).string());
  const auto files = manifest["files"].get<std::vector<std::string>>();
  for (const char* f : {"summary.json", "contact.csv", "vehicles.csv", "footprint_force.csv",
                        "footprint_displacement.csv", "footprint_velocity.csv", "interface.csv"})
    EXPECT_THAT(files, ::testing::Contains(f));
}

TEST(CliResults, AnotherScenariosResultsAreReplacedOnlyWithOverwrite) {
  const auto dir = scratch_directory("results_other_scenario");
  const auto a = dir / "a.json", b = dir / "b.json";
  nlohmann::json s = small_scenario();
  write_text(a, s.dump());
  s["name"] = "scenario b";
  write_text(b, s.dump());
  ASSERT_EQ(run_rumble({"run", a.string(), "--no-progress"}).exit_code, 0);
  const CliResult refused = run_rumble({"run", b.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output,
              HasSubstr("results directory " + (dir / "results").string() +
                        " holds the results of another scenario (" + fs::canonical(a).string() +
                        ", says " + (dir / "results" / ".rumble-manifest.json").string() + ")"));
  EXPECT_THAT(refused.output, HasSubstr("Choose another directory (/outputs/directory, or "
                                        "--output DIR), or pass --overwrite to write here"));
  EXPECT_EQ(read_json(dir / "results" / "summary.json")["scenario_file"], a.string());
  const CliResult overwritten = run_rumble({"run", b.string(), "--no-progress", "--overwrite"});
  EXPECT_EQ(overwritten.exit_code, 0) << overwritten.output;
  EXPECT_EQ(read_json(dir / "results" / "summary.json")["scenario"]["name"], "scenario b");
  // b's results now: its own rerun needs no --overwrite.
  EXPECT_EQ(run_rumble({"run", b.string(), "--no-progress"}).exit_code, 0);
}

TEST(CliResults, FilesNoManifestListsAreRefusedAndNeverDeleted) {
  const auto dir = scratch_directory("results_unlisted");
  const auto path = write_scenario(dir, small_scenario());
  const auto results = dir / "results";
  ASSERT_EQ(run_rumble({"run", path.string(), "--no-progress"}).exit_code, 0);
  write_text(results / "notes.txt", "mine");
  fs::create_directories(results / "plots_by_hand");
  const CliResult refused = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("holds 2 files that no rumble manifest lists (notes.txt, "
                                        "plots_by_hand/)"));
  EXPECT_THAT(refused.output, HasSubstr("pass --overwrite to write here anyway"));
  // A manifest that names something outside the directory is not obeyed, even with --overwrite.
  write_text(dir / "outside.txt", "not a result");
  auto manifest = read_json(results / ".rumble-manifest.json");
  manifest["files"].push_back("../outside.txt");
  write_text(results / ".rumble-manifest.json", manifest.dump());
  const CliResult overwritten = run_rumble({"run", path.string(), "--no-progress", "--overwrite"});
  EXPECT_EQ(overwritten.exit_code, 0) << overwritten.output;
  EXPECT_EQ(file_text(results / "notes.txt"), "mine");
  EXPECT_TRUE(fs::is_directory(results / "plots_by_hand"));
  EXPECT_EQ(file_text(dir / "outside.txt"), "not a result");
  EXPECT_EQ(csv_rows(results / "contact.csv"), 51u);
}

// `rumble soil-frf` writes beside a scenario's results by default: runs leave that alone.
TEST(CliResults, SoilFrfOutputBesideTheResultsIsLeftAlone) {
  const auto dir = scratch_directory("results_soil_frf");
  const auto path = write_scenario(dir, small_scenario()).string();
  const CliResult frf = run_rumble({"soil-frf", path, "--no-plot"});
  ASSERT_EQ(frf.exit_code, 0) << frf.output;
  const CliResult run = run_rumble({"run", path, "--no-progress"});
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run_rumble({"run", path, "--no-progress"}).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir / "results" / "soil_frf" / "scenario_winkler.csv"));
}

// A directory that holds results of a rumble without manifests is refused, not emptied.
TEST(CliResults, ResultsWithoutAManifestAreRefused) {
  const auto dir = scratch_directory("results_no_manifest");
  fs::create_directories(dir / "results");
  write_text(dir / "results" / "contact.csv", "t [s]\n0\n");
  const CliResult r = run_rumble({"run", write_scenario(dir, small_scenario()).string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("holds 1 file that no rumble manifest lists (contact.csv), e.g. "
                                  "the results of an older rumble"));
  EXPECT_EQ(file_text(dir / "results" / "contact.csv"), "t [s]\n0\n");
}

// ---- where results may go

TEST(CliResults, ADirectoryLeavingTheScenarioFolderNeedsConsent) {
  const auto dir = scratch_directory("results_outside");
  fs::create_directories(dir / "sub");
  nlohmann::json s = small_scenario();
  s["outputs"]["directory"] = "../escaped";
  const auto path = write_scenario(dir / "sub", s);
  const CliResult refused = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output,
              HasSubstr("error: /outputs/directory: \"../escaped\" leaves the scenario's folder " +
                        (dir / "sub").string() + " (it is " + (dir / "escaped").string() + ")"));
  EXPECT_THAT(refused.output,
              HasSubstr("hint: results go inside the scenario's folder unless the command line "
                        "says otherwise: choose the directory with --output DIR, or pass "
                        "--allow-outside-results to write to " +
                        (dir / "escaped").string()));
  EXPECT_FALSE(fs::exists(dir / "escaped"));
  const CliResult allowed =
      run_rumble({"run", path.string(), "--no-progress", "--allow-outside-results"});
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_EQ(csv_rows(dir / "escaped" / "contact.csv"), 51u);
}

TEST(CliResults, ADirectoryOutsideIsRefusedBeforeTheSoilIsBuilt) {
  // Building a FEM soil meshes it (minutes on a large mesh): the refusal must come first. Here
  // the soil's construction would fail (the sleepers do not fit in a 2 m hemisphere), and is not
  // reached.
  const auto dir = scratch_directory("results_outside_first");
  nlohmann::json s = small_fem_scenario();
  s["soil"]["params"]["mesh"]["radius"] = 2.0;
  s["outputs"]["directory"] = (dir / "absolute").string();
  const CliResult refused = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("is an absolute path"));
  EXPECT_THAT(refused.output, Not(HasSubstr("/soil")));
}

TEST(CliResults, AnAbsoluteDirectoryNeedsConsent) {
  const auto dir = scratch_directory("results_absolute");
  nlohmann::json s = small_scenario();
  s["outputs"]["directory"] = (dir / "absolute").string();
  const auto path = write_scenario(dir, s);
  const CliResult refused = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("/outputs/directory: \"" + (dir / "absolute").string() +
                                        "\" is an absolute path"));
  EXPECT_THAT(refused.output,
              HasSubstr("--allow-outside-results to write to " + (dir / "absolute").string()));
  EXPECT_FALSE(fs::exists(dir / "absolute"));
  const CliResult chosen =
      run_rumble({"run", path.string(), "--no-progress", "--output", (dir / "chosen").string()});
  EXPECT_EQ(chosen.exit_code, 0) << chosen.output;
  EXPECT_EQ(csv_rows(dir / "chosen" / "contact.csv"), 51u);
  EXPECT_FALSE(fs::exists(dir / "absolute"));
}

// Read from /dev/stdin, "results" would land in /dev; the command line must say where.
TEST(CliResults, AScenarioFromStdinNeedsADirectoryOnTheCommandLine) {
  const auto dir = scratch_directory("results_stdin");
  RunSetup setup;
  setup.stdin_file = write_scenario(dir, small_scenario());
  const CliResult refused = run_rumble({"run", "/dev/stdin", "--no-progress"}, setup);
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output,
              HasSubstr("/outputs/directory: the scenario is read from /dev/stdin, not from a "
                        "file in a folder, so \"results\" would be /dev/results"));
  EXPECT_THAT(refused.output, HasSubstr("choose the directory with --output DIR"));
  const CliResult chosen = run_rumble(
      {"run", "/dev/stdin", "--no-progress", "--output", (dir / "from_stdin").string()}, setup);
  EXPECT_EQ(chosen.exit_code, 0) << chosen.output;
  EXPECT_EQ(csv_rows(dir / "from_stdin" / "contact.csv"), 51u);
}

// ---- never through a link

// A link planted at a results file's name (contact.csv, the summary's temporary file) is
// replaced by the file; its target is never written.
TEST(CliResults, LinksInTheResultsDirectoryAreReplacedNeverFollowed) {
  const auto dir = scratch_directory("results_links");
  const auto path = write_scenario(dir, small_scenario());
  const auto results = dir / "results";
  fs::create_directories(results);
  for (const char* f : {"precious_csv.txt", "precious_tmp.txt", "precious_vehicles.txt"})
    write_text(dir / f, "keep me");
  fs::create_symlink(dir / "precious_csv.txt", results / "contact.csv");
  fs::create_symlink(dir / "precious_tmp.txt", results / "summary.json.tmp");
  const CliResult r = run_rumble({"run", path.string(), "--no-progress", "--overwrite"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file_text(dir / "precious_csv.txt"), "keep me");
  EXPECT_EQ(file_text(dir / "precious_tmp.txt"), "keep me");
  EXPECT_FALSE(fs::is_symlink(results / "contact.csv"));
  EXPECT_EQ(csv_rows(results / "contact.csv"), 51u);
  // A link put in place of a listed file after the run: the rerun removes the link.
  fs::remove(results / "vehicles.csv");
  fs::create_symlink(dir / "precious_vehicles.txt", results / "vehicles.csv");
  const CliResult again = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(file_text(dir / "precious_vehicles.txt"), "keep me");
  EXPECT_EQ(csv_rows(results / "vehicles.csv"), 51u);
}

}  // namespace
}  // namespace rumble::testing
