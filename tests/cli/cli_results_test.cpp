// What a run does with its results directory (issue #8): one run at a time (a lock naming the
// holder), and no write goes through a symbolic link.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

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
