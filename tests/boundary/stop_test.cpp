// Ctrl-C reaches a plugin inside a long advance: the host's progress callback (ABI 1.1) reports
// the stop request, the plugin returns, and the run ends "interrupted" with what it recorded so
// far, instead of waiting for a soil that may run for minutes. picky_soil stalls in its first step
// starting after 0.0095 s (t = 0.01 s), for 60 s at most, in 10 ms slices, asking the host each
// time.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "boundary_support.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "run/run_scenario.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

/// A run of scenario s (in scratch directory `name`) with Ctrl-C requested 0.5 s in: how it ended
/// (the outcome, or the Interrupted it threw), where its results are and how long it took.
struct StoppedRun {
  RunOutcome outcome;
  std::string thrown;  // Interrupted's message, when the run threw it
  std::filesystem::path results_dir;
  double seconds = 0.0;
};

StoppedRun run_with_ctrl_c(const nlohmann::json& s, const std::string& name) {
  const auto path = write_scenario(scratch_directory(name), s);
  PluginRegistry registry;
  auto doc = cli::prepare_scenario(path, registry, scenario::Format::kText);
  if (!doc) throw std::runtime_error("the fixture scenario does not validate");
  clear_interrupt();
  const auto start = std::chrono::steady_clock::now();
  std::thread ctrl_c([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    request_interrupt();
  });
  const scenario::RunSpec spec = scenario::make_run_spec(doc->json, path);
  ResultsDirectory results(spec.outputs.directory, spec.path, false);
  StoppedRun run;
  run.results_dir = results.path();
  try {
    run.outcome = run_scenario(spec, registry, results, RunOptions{});
  } catch (const Interrupted& e) {
    run.thrown = e.what();
  }
  ctrl_c.join();
  clear_interrupt();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

TEST(Stop, RequestReachesAPluginInsideALongAdvance) {
  const StoppedRun run =
      run_with_ctrl_c(fixture_scenario({{"type", "picky_soil"}, {"params", {{"stall_at", 0.0095}}}},
                                       {{"type", "gauss_seidel"}}),
                      "stop_inside_advance");
  const RunOutcome& outcome = run.outcome;
  EXPECT_EQ(outcome.status, RunStatus::kInterrupted) << outcome.message;
  EXPECT_EQ(outcome.exit_code, 3);
  EXPECT_LT(run.seconds, 30.0);  // the stall lasts 60 s unless the stop reached it
  EXPECT_NE(outcome.message.find("inside the step after t = 0.01"), std::string::npos)
      << outcome.message;
  EXPECT_EQ(read_json(outcome.results_dir / "summary.json")["status"], "interrupted");
  EXPECT_EQ(csv_rows(outcome.results_dir / "contact.csv"), 11u);  // t = 0 .. 0.01 s
}

// Ctrl-C inside a soil's static solve (a FEM soil's take tens of seconds at a million DOFs, and
// it looks for the request between its iterations): the run ends "interrupted" before the first
// step, says so, and summary.json records it, not a failure.
TEST(Stop, RequestReachesAPluginInsideItsStatics) {
  const StoppedRun run = run_with_ctrl_c(
      fixture_scenario({{"type", "picky_soil"}, {"params", {{"stall_in_statics", true}}}},
                       {{"type", "gauss_seidel"}}),
      "stop_inside_statics");
  EXPECT_LT(run.seconds, 30.0);  // the stall lasts 60 s unless the stop reached it
  EXPECT_NE(run.thrown.find("interrupted (Ctrl-C) while the static state was solved, before the "
                            "first step"),
            std::string::npos)
      << run.thrown;
  EXPECT_EQ(read_json(run.results_dir / "summary.json")["status"], "interrupted");
}

// Ctrl-C or SIGTERM in a phase that cannot look for it (a dense LU, gmsh, a plugin's long call
// that never asks the host) still ends the run within a second or two (issue #30 item 2): at
// the deadline (core/interrupt.hpp) summary.json says "interrupted" and which phase held it,
// the rows written so far stay, and the exit code is an interrupted run's. picky_soil, deaf,
// stalls 60 s in its statics or in the step from t = 0.01 s.
std::filesystem::path expect_stopped_at_deadline(const std::string& name,
                                                 const nlohmann::json& soil_params, int signal,
                                                 const std::string& phase) {
  const auto dir = scratch_directory(name);
  const auto path =
      write_scenario(dir, fixture_scenario({{"type", "picky_soil"}, {"params", soil_params}},
                                           {{"type", "gauss_seidel"}}));
  const auto output = dir / "output.txt";
  const pid_t pid = start_rumble({"run", path.string(), "--no-progress"}, output);
  const auto summary_file = dir / "results" / "summary.json";
  for (int i = 0; i < 600 && !std::filesystem::exists(summary_file); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // inside the stall
  const auto start = std::chrono::steady_clock::now();
  kill(pid, signal);
  const int exit_code = wait_rumble(pid);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(exit_code, 3) << file_text(output);
  EXPECT_GT(seconds, kStopGraceSeconds - 0.1);  // the phase had its grace
  EXPECT_LT(seconds, kStopGraceSeconds + 1.5);  // and no more (the stall lasts 60 s)
  const std::string cause = signal == SIGTERM ? "SIGTERM" : "Ctrl-C";
  EXPECT_THAT(file_text(output),
              HasSubstr("rumble: error: stopped by " + cause + ": " + phase +
                        " did not stop within 1.5 s of the request, so the process ends here"));
  const nlohmann::json summary = read_json(summary_file);
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["message"], "interrupted (" + cause + "): " + phase +
                                    " did not stop within 1.5 s of the request, so the process "
                                    "ended there");
  return dir / "results";
}

TEST(Stop, CtrlCInAStaticSolveThatNeverLooksEndsTheRunAtTheDeadline) {
  expect_stopped_at_deadline("deadline_statics", {{"stall_in_statics", true}, {"deaf", true}},
                             SIGINT, "the static state");
}

TEST(Stop, SigtermInAStepThatNeverLooksEndsTheRunAtTheDeadlineWithItsRows) {
  const auto results = expect_stopped_at_deadline(
      "deadline_step", {{"stall_at", 0.0095}, {"deaf", true}}, SIGTERM, "the time stepping");
  // t = 0 .. 0.01 s were recorded before the stall: on disk, row by row (results/csv_file.hpp).
  EXPECT_EQ(csv_rows(results / "contact.csv"), 11u);
}

// A plugin calling exit(0) mid-run ended rumble with exit code 0, a truncated run and
// summary.json "running" (issue #8): the exit is intercepted, the run is "aborted", exit code 3.
TEST(Stop, PluginCallingExitAbortsTheRunVisibly) {
  const nlohmann::json s = fixture_scenario(
      {{"type", "picky_soil"}, {"params", {{"exit_at", 0.0195}}}}, {{"type", "gauss_seidel"}});
  CliResult r;
  const auto results = run_in("plugin_calls_exit", s, r);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("rumble: error: the process was told to exit during the run (a plugin "
                          "called exit()?)"),
            std::string::npos)
      << r.output;
  const nlohmann::json summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "aborted");
  EXPECT_NE(summary["message"].get<std::string>().find("exit()"), std::string::npos);
  EXPECT_LE(csv_rows(results / "contact.csv"), 21u);  // at most t = 0 .. 0.02 s
}

// A plugin that crashed left summary.json "running" for ever (issue #30 item 4): the crash is
// recorded before the process ends, with the signal and the participant that was stepping, and
// the process ends as the signal ends it (128 + 11), with the results so far on disk.
TEST(Stop, APluginThatCrashesLeavesTheSignalAndItsNameInTheSummary) {
  const nlohmann::json s = fixture_scenario(
      {{"type", "picky_soil"}, {"params", {{"crash_at", 0.0195}}}}, {{"type", "gauss_seidel"}});
  CliResult r;
  const auto results = run_in("plugin_crashes", s, r);
  EXPECT_EQ(r.exit_code, 128 + SIGSEGV) << r.output;
  const nlohmann::json summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "crashed");
  EXPECT_EQ(summary["crash"]["signal"], "SIGSEGV");
  EXPECT_EQ(summary["crash"]["participant"], "soil/picky_soil");
  EXPECT_TRUE(summary["heartbeat"].is_object());      // the last one written (about once a second)
  EXPECT_EQ(csv_rows(results / "contact.csv"), 21u);  // t = 0 .. 0.02 s, then the crash
}

}  // namespace
}  // namespace rumble::testing
