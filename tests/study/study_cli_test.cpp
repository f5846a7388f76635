// `rumble study` end to end on small Winkler scenarios (0.05 s each): parallel runs, study.json,
// up-to-date runs skipped, changed runs rerun, failing runs reported while the others complete,
// Ctrl-C, and the command's messages.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "cli_runner.hpp"
#include "core/cpu_affinity.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

fs::path write_study(const fs::path& dir, const json& study) {
  const auto path = dir / "study.json";
  std::ofstream(path) << study.dump(2) << '\n';
  return path;
}

json two_by_two(double stiff_k) {
  return json::parse(R"({"study_version": 1, "name": "two by two", "description": "a test",
    "scenario": "scenario.json", "output": "out", "jobs": 2,
    "axes": [{"name": "soil", "values": {"soft": {"/soil/params/k": 5e7},
                                         "stiff": {"/soil/params/k": )" +
                     std::to_string(stiff_k) + R"(}}},
             {"name": "coupling", "values": {"gs": {"/coupling/type": "gauss_seidel"},
                                             "jacobi": {"/coupling/type": "jacobi"}}}]})");
}

std::map<std::string, json> runs_by_name(const json& state) {
  std::map<std::string, json> out;
  for (const json& r : state["runs"]) out[r["name"].get<std::string>()] = r;
  return out;
}

TEST(Study, RunsTheProductSkipsWhatIsUpToDateAndRerunsWhatChanged) {
  const auto dir = scratch_directory("study_2x2");
  write_scenario(dir, small_scenario());
  const auto study = write_study(dir, two_by_two(2e8));
  const CliResult first = run_rumble({"study", study.string(), "--no-report"});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_THAT(first.output, HasSubstr("study: two by two: 4 runs: 4 to run, 0 up to date "
                                      "(skipped), 0 not valid; 2 at a time"));
  EXPECT_THAT(first.output, HasSubstr("study: started soft-gs (1 of 4)"));
  EXPECT_THAT(first.output, HasSubstr("study: completed stiff-jacobi in "));
  EXPECT_THAT(first.output, HasSubstr("4 of 4 done"));
  EXPECT_THAT(first.output, HasSubstr("1 of 4 done, ETA "));
  EXPECT_THAT(first.output, HasSubstr("study: 4 completed, 0 up to date (skipped), 0 failed"));

  const json state = read_json(dir / "out" / "study.json");
  EXPECT_EQ(state["name"], "two by two");
  EXPECT_EQ(state["description"], "a test");
  EXPECT_EQ(state["status"], "completed");
  EXPECT_EQ(state["jobs"], 2);
  EXPECT_EQ(state["axes"], json::parse(R"([{"name": "soil", "values": ["soft", "stiff"]},
                                          {"name": "coupling", "values": ["gs", "jacobi"]}])"));
  ASSERT_EQ(state["runs"].size(), 4u);
  std::vector<std::string> order;
  for (const json& r : state["runs"]) order.push_back(r["name"]);
  EXPECT_EQ(order,
            (std::vector<std::string>{"soft-gs", "soft-jacobi", "stiff-gs", "stiff-jacobi"}));
  for (const json& r : state["runs"]) {
    const std::string name = r["name"];
    EXPECT_EQ(r["status"], "completed") << name;
    EXPECT_EQ(r["exit_code"], 0) << name;
    EXPECT_EQ(r["key"].get<std::string>().size(), 64u) << name;
    EXPECT_GT(r["wall_time_s"].get<double>(), 0.0) << name;
    EXPECT_EQ(fs::path(r["results"].get<std::string>()), fs::absolute(dir / "out" / name));
    const json summary = read_json(dir / "out" / name / "summary.json");
    EXPECT_EQ(summary["status"], "completed") << name;
    // Two at a time: each run on its half of the CPUs, not on all of them.
    const auto cpus = summary["process"]["cpus"].get<std::vector<int>>();
    const std::vector<int> all = usable_cpu_list();
    EXPECT_TRUE(cpus == cpu_share(all, 0, 2) || cpus == cpu_share(all, 1, 2))
        << name << ": " << summary["process"]["cpus"];
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / name / "run.log")) << name;
  }
  const auto first_runs = runs_by_name(state);
  EXPECT_EQ(first_runs.at("stiff-jacobi")["axis_values"],
            json::parse(R"({"soil": "stiff", "coupling": "jacobi"})"));
  EXPECT_EQ(first_runs.at("stiff-jacobi")["patches"],
            json::parse(R"([{"pointer": "/soil/params/k", "value": 2e8},
                            {"pointer": "/coupling/type", "value": "jacobi"}])"));
  const json soft_jacobi = read_json(dir / "out" / "soft-jacobi" / "summary.json");
  EXPECT_EQ(soft_jacobi["scenario"]["soil"]["params"]["k"], 5e7);
  EXPECT_EQ(soft_jacobi["scenario"]["coupling"]["type"], "jacobi");
  EXPECT_NE(first_runs.at("soft-gs")["key"], first_runs.at("soft-jacobi")["key"]);

  // Again: all up to date.
  const CliResult second = run_rumble({"study", study.string(), "--no-report"});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_THAT(second.output, HasSubstr("4 runs: 0 to run, 4 up to date (skipped)"));
  EXPECT_THAT(second.output, Not(HasSubstr("started")));
  // Kept in a variable: a range-for over a member of a temporary reads freed memory.
  const json second_state = read_json(dir / "out" / "study.json");
  for (const json& r : second_state["runs"]) {
    EXPECT_EQ(r["status"], "skipped") << r["name"];
    EXPECT_EQ(r["key"], first_runs.at(r["name"].get<std::string>())["key"]);
  }

  // One value changed: only the runs it touches run again.
  write_study(dir, two_by_two(3e8));
  const CliResult dry = run_rumble({"study", study.string(), "--dry-run"});
  EXPECT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_THAT(dry.output, HasSubstr("soft-gs: up to date (skipped)\n"));
  EXPECT_THAT(dry.output, HasSubstr("stiff-gs: would run\n"));
  const CliResult third = run_rumble({"study", study.string(), "--jobs", "1", "--no-report"});
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_THAT(third.output, HasSubstr("4 runs: 2 to run, 2 up to date (skipped), 0 not valid; 1 "
                                      "at a time"));
  const auto after = runs_by_name(read_json(dir / "out" / "study.json"));
  EXPECT_EQ(after.at("soft-gs")["status"], "skipped");
  EXPECT_EQ(after.at("soft-jacobi")["status"], "skipped");
  EXPECT_EQ(after.at("stiff-gs")["status"], "completed");
  EXPECT_EQ(after.at("stiff-jacobi")["status"], "completed");
  EXPECT_EQ(read_json(dir / "out" / "stiff-gs" / "summary.json")["scenario"]["soil"]["params"]["k"],
            3e8);

  // The base scenario changed: every run is out of date; --force reruns all.
  json s = small_scenario();
  s["time"]["end"] = 0.04;
  write_scenario(dir, s);
  EXPECT_THAT(run_rumble({"study", study.string(), "--dry-run"}).output,
              HasSubstr("4 runs: 4 to run, 0 up to date"));
  write_scenario(dir, small_scenario());
  EXPECT_THAT(run_rumble({"study", study.string(), "--dry-run"}).output,
              HasSubstr("4 runs: 0 to run, 4 up to date"));
  EXPECT_THAT(run_rumble({"study", study.string(), "--dry-run", "--force"}).output,
              HasSubstr("4 runs: 4 to run, 0 up to date"));
}

TEST(Study, FailingRunsAreReportedAndTheOthersComplete) {
  const auto dir = scratch_directory("study_failing");
  write_scenario(dir, small_scenario());
  // "diverges": a soft massless soil under Gauss-Seidel (tests/cli DivergingCouplingStops...).
  const auto study = write_study(dir, json::parse(R"({"study_version": 1,
    "scenario": "scenario.json", "output": "out",
    "runs": [{"name": "good"},
             {"name": "diverges", "set": {"/soil": {"type": "clm",
                                                     "params": {"E": 1e7, "nu": 0.3, "rho": 1800}},
                                            "/time/end": 0.2}},
             {"name": "invalid", "set": {"/soil/params/k": -1}},
             {"name": "no-vehicle", "set": {"/vehicles/3/speed": 10}}]})"));
  const CliResult r = run_rumble({"study", study.string(), "--jobs=2", "--no-report"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("study: run invalid is not valid:\n"));
  EXPECT_THAT(r.output, HasSubstr("error: /soil/params/k: must be"));
  EXPECT_THAT(r.output, HasSubstr("got -1 (set by the study, /runs/2/set/~1soil~1params~1k)"));
  EXPECT_THAT(r.output, HasSubstr("study: run no-vehicle is not valid:\n" + study.string() +
                                  ": /runs/3/set/~1vehicles~13~1speed: /vehicles/3/speed = 10: "
                                  "/vehicles is an array (it has 1 element, index 0)"));
  EXPECT_THAT(r.output, HasSubstr("4 runs: 2 to run, 0 up to date (skipped), 2 not valid"));
  EXPECT_THAT(r.output, HasSubstr("study: FAILED diverges in "));
  EXPECT_THAT(r.output, HasSubstr("(exit code 3): simulation diverged at t = "));
  EXPECT_THAT(r.output, HasSubstr("study: 1 completed, 0 up to date (skipped), 3 failed"));
  const auto runs = runs_by_name(read_json(dir / "out" / "study.json"));
  EXPECT_EQ(runs.at("good")["status"], "completed");
  EXPECT_EQ(runs.at("diverges")["status"], "failed");
  EXPECT_EQ(runs.at("diverges")["exit_code"], 3);
  EXPECT_THAT(runs.at("diverges")["message"].get<std::string>(),
              HasSubstr("simulation diverged at t = "));
  EXPECT_EQ(runs.at("invalid")["status"], "failed");
  EXPECT_TRUE(runs.at("invalid")["key"].is_null());
  EXPECT_TRUE(runs.at("invalid")["exit_code"].is_null());
  EXPECT_THAT(runs.at("invalid")["message"].get<std::string>(),
              HasSubstr("not valid: /soil/params/k: must be"));
  EXPECT_EQ(read_json(dir / "out" / "study.json")["status"], "failed");
  EXPECT_EQ(read_json(dir / "out" / "good" / "summary.json")["status"], "completed");
  EXPECT_FALSE(fs::exists(dir / "out" / "invalid"));
  // The failed run runs again next time; the good one is up to date.
  EXPECT_THAT(run_rumble({"study", study.string(), "--dry-run"}).output,
              HasSubstr("4 runs: 1 to run, 1 up to date (skipped), 2 not valid"));
}

/// Starts a study of `runs` (run objects) of a scenario long enough to be stopped (6000 macro
/// steps), one at a time, into dir/out; returns once its first run has recorded 20 rows (or
/// 30 s have passed).
pid_t start_long_study(const fs::path& dir, const std::string& runs) {
  json s = small_scenario();
  s["time"]["end"] = 0.6;
  s["time"]["macro_step"] = 1e-4;
  s["track"]["sleepers"]["count"] = 40;
  write_scenario(dir, s);
  const auto study = write_study(dir, json::parse(R"({"study_version": 1,
    "scenario": "scenario.json", "output": "out", "jobs": 1, "runs": )" +
                                                  runs + "}"));
  const pid_t pid = start_rumble({"study", study.string()});
  const auto contact = dir / "out" / "first" / "contact.csv";
  for (int i = 0; i < 600 && csv_rows(contact) < 20; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  return pid;
}

TEST(Study, InterruptStopsTheRunsAndRecordsTheState) {
  const auto dir = scratch_directory("study_interrupt");
  const pid_t pid = start_long_study(dir, R"([{"name": "first"}, {"name": "second"}])");
  kill(pid, SIGINT);
  EXPECT_EQ(wait_rumble(pid), 3);
  const json state = read_json(dir / "out" / "study.json");
  EXPECT_EQ(state["status"], "interrupted");
  const auto runs = runs_by_name(state);
  EXPECT_EQ(runs.at("first")["status"], "interrupted");
  EXPECT_EQ(runs.at("second")["status"], "interrupted");
  EXPECT_EQ(runs.at("second")["message"], "not started: the study was interrupted");
  EXPECT_EQ(read_json(dir / "out" / "first" / "summary.json")["status"], "interrupted");
  EXPECT_FALSE(fs::exists(dir / "out" / "second" / "summary.json"));
}

// A study killed outright (SIGKILL: no handler runs) left its run orphaned and still writing
// (issue #30 item 4); its runs now get SIGTERM from the kernel when it dies and stop as an
// interrupted run does, with what they finished on disk.
TEST(Study, ItsRunsDieWithAStudyKilledOutright) {
  const auto dir = scratch_directory("study_killed");
  const pid_t pid = start_long_study(dir, R"([{"name": "first"}])");
  const auto run = dir / "out" / "first";
  kill(pid, SIGKILL);
  wait_rumble(pid);
  std::string status;
  for (int i = 0; i < 100 && status != "interrupted"; ++i) {  // 5 s at most
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    status = read_json(run / "summary.json").value("status", "");
  }
  EXPECT_EQ(status, "interrupted");
  EXPECT_THAT(read_json(run / "summary.json").value("message", ""), HasSubstr("SIGTERM"));
}

// A run beyond the size limits (issue #8) is not valid in a study either, unless the study says
// --yes (its child `rumble run` then gets --yes too). The scenario's own outputs.directory, a
// file here, is no concern of a study: each run writes to its --output directory. The huge run
// is the longest the schema's ranges allow (an hour in macro steps of 1e-7 s, the vehicle
// standing so that it stays on the rail; docs/scenario.md, "Limits").
TEST(Study, RunSizeLimitsAndTheirConfirmation) {
  const auto dir = scratch_directory("study_run_size");
  nlohmann::json s = small_scenario();
  std::ofstream(dir / "results") << "a file where the scenario's results would go\n";
  write_scenario(dir, s);
  const auto study = write_study(dir, json::parse(R"({"study_version": 1,
    "scenario": "scenario.json", "output": "out",
    "runs": [{"name": "small"}, {"name": "huge", "set": {"/time/end": 3600, "/time/macro_step": 1e-7,
                                                        "/vehicles/0/speed": 0}}]})"));
  const CliResult refused = run_rumble({"study", study.string(), "--dry-run"});
  EXPECT_THAT(refused.output, HasSubstr("study: run huge is not valid:\n"));
  EXPECT_THAT(refused.output, HasSubstr("/time/macro_step: the run takes 3.6e+10 macro steps"));
  EXPECT_THAT(refused.output, HasSubstr("2 runs: 1 to run, 0 up to date (skipped), 1 not valid"));
  const CliResult confirmed = run_rumble({"study", study.string(), "--dry-run", "--yes"});
  EXPECT_THAT(confirmed.output, HasSubstr("2 runs: 2 to run, 0 up to date (skipped), 0 not valid"))
      << confirmed.output;
}

/// What `dir` holds, every level, as paths relative to it.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    out.push_back(e.path().lexically_relative(dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

// A study's results stay inside the study file's folder unless the command line says otherwise
// (issue 30), and --dry-run writes nothing at all.
TEST(Study, AnOutputOutsideTheStudyFilesFolderNeedsConsent) {
  const auto dir = scratch_directory("study_output_outside");
  fs::create_directories(dir / "sub");
  fs::create_directories(dir / "elsewhere");
  write_scenario(dir / "sub", small_scenario());
  fs::create_directory_symlink(dir / "elsewhere", dir / "sub" / "out");
  json s = json::parse(R"({"study_version": 1, "scenario": "scenario.json",
                           "output": "out/s", "runs": [{"name": "a"}]})");
  const auto link = write_study(dir / "sub", s);
  s["output"] = "../escaped";
  std::ofstream(dir / "sub" / "escaping.json") << s.dump(2) << '\n';
  const auto before = listing(dir);
  for (const fs::path& study : {link, dir / "sub" / "escaping.json"}) {
    for (const char* dry : {"--dry-run", "--no-report"}) {
      const CliResult r = run_rumble({"study", study.string(), dry});
      EXPECT_EQ(r.exit_code, 1) << r.output;
      EXPECT_THAT(r.output, HasSubstr(study.string() + ":2:13: error: /output: "));
      EXPECT_THAT(r.output, HasSubstr("    hint: results go inside the study file's folder unless "
                                      "the command line says otherwise: pass "
                                      "--allow-outside-results to write to "));
    }
  }
  const fs::path real = fs::canonical(dir);
  EXPECT_THAT(run_rumble({"study", link.string()}).output,
              HasSubstr("error: /output: \"out/s\" leads out of the study file's folder " +
                        (dir / "sub").string() + " through the symbolic link " +
                        (real / "sub" / "out").string() + " (it is " +
                        (real / "elsewhere" / "s").string() + ")"));
  EXPECT_EQ(listing(dir), before);  // nothing made, nothing written
  const CliResult dry =
      run_rumble({"study", link.string(), "--dry-run", "--allow-outside-results"});
  EXPECT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_THAT(dry.output, HasSubstr("a: would run"));
  EXPECT_EQ(listing(dir), before);
  const CliResult allowed =
      run_rumble({"study", link.string(), "--no-report", "--allow-outside-results"});
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_EQ(read_json(dir / "elsewhere" / "s" / "a" / "summary.json")["status"], "completed");
}

// A run's directory in the output folder that is a link (or a file) is left alone, and the run
// is not valid: its results (and the --overwrite the study gives it) would go where it leads.
TEST(Study, ARunDirectoryThatIsALinkIsNeverFollowed) {
  const auto dir = scratch_directory("study_run_link");
  write_scenario(dir, small_scenario());
  fs::create_directories(dir / "out");
  fs::create_directories(dir / "elsewhere");
  fs::create_directory_symlink(dir / "elsewhere", dir / "out" / "a");
  std::ofstream(dir / "out" / "b") << "mine\n";
  const auto study = write_study(dir, json::parse(R"({"study_version": 1,
    "scenario": "scenario.json", "output": "out", "runs": [{"name": "a"}, {"name": "b"},
    {"name": "c"}]})"));
  const CliResult r = run_rumble({"study", study.string(), "--no-report"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("study: run a is not valid:\nits results directory " +
                                  (dir / "out" / "a").string() + " is a symbolic link (to " +
                                  (dir / "elsewhere").string() +
                                  "); a study writes each run's results into a real directory of "
                                  "its output folder and never through a link nor over what "
                                  "stands there: move it away"));
  EXPECT_THAT(r.output, HasSubstr("study: run b is not valid:\nits results directory " +
                                  (dir / "out" / "b").string() + " is a file;"));
  EXPECT_THAT(r.output, HasSubstr("3 runs: 1 to run, 0 up to date (skipped), 2 not valid"));
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
  EXPECT_TRUE(fs::is_symlink(dir / "out" / "a"));
  EXPECT_EQ(file_text(dir / "out" / "b"), "mine\n");
  EXPECT_EQ(read_json(dir / "out" / "c" / "summary.json")["status"], "completed");
}

TEST(Study, Messages) {
  const auto dir = scratch_directory("study_messages");
  write_scenario(dir, small_scenario());
  const auto study = write_study(dir, json::parse(R"({"study_version": 1,
    "scenario": "scenario.json", "output": "out", "runs": [{"name": "a"}]})"));

  CliResult r = run_rumble({"study"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(
      r.output,
      HasSubstr("rumble: error: usage: rumble study FILE [--jobs N] [--force] [--dry-run]"));
  r = run_rumble({"study", study.string(), "--jobs", "0"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("rumble: error: --jobs=0 is not a number of runs at once; give "
                                  "an integer from 1 to 1024"));
  r = run_rumble({"study", (dir / "nope.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("nope.json: error: file not found"));

  // Problems in the study file: compiler-style, with line:col, and nothing runs.
  std::ofstream(dir / "bad.json")
      << "{\n  \"study_version\": 1,\n  \"scenario\": \"scenario.json\",\n"
         "  \"axis\": [],\n  \"runs\": [{\"name\": \"a b\"}]\n}\n";
  r = run_rumble({"study", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("bad.json:4:11: error: /axis: unknown key 'axis' in a study"));
  EXPECT_THAT(r.output, HasSubstr("    hint: did you mean \"axes\"?"));
  EXPECT_THAT(r.output, HasSubstr("bad.json:5:21: error: /runs/0/name: run name 'a b' cannot "
                                  "name a directory"));
  EXPECT_THAT(r.output, HasSubstr("2 errors"));
  EXPECT_FALSE(fs::exists(dir / "results"));

  // Another study holds the output folder.
  fs::create_directories(dir / "out");
  const int fd = open((dir / "out" / ".rumble-study.lock").c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(write(fd, "4242\n", 5), 5);
  ASSERT_EQ(flock(fd, LOCK_EX), 0);
  r = run_rumble({"study", study.string(), "--no-report"});
  close(fd);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is in use by another rumble study (process id 4242); wait for "
                                  "it to end, or set another \"output\" in the study file"));
}

}  // namespace
}  // namespace rumble::testing
