// `rumble study FILE [--jobs N] [--force] [--dry-run] [--allow-outside-results]`: the runs of a
// study file (a product of scenario variations and/or a list), each validated first, then run as
// child processes, at most N at once, skipping those whose results are up to date; the state in
// OUTPUT/study.json. docs/study.md.
#include <algorithm>
#include <functional>
#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plot_script.hpp"
#include "core/cpu_affinity.hpp"
#include "core/interrupt.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/registry.hpp"
#include "scenario/report.hpp"
#include "study/expansion.hpp"
#include "study/output_lock.hpp"
#include "study/prepare_runs.hpp"
#include "study/rank_share.hpp"
#include "study/runner.hpp"
#include "study/study_file.hpp"
#include "study/study_state.hpp"

namespace rumble::cli {
namespace {

namespace fs = std::filesystem;
using study::RunRecord;
using study::RunState;

constexpr const char* kStudyUsage =
    "usage: rumble study FILE [--jobs N] [--force] [--dry-run] [--no-report] [--yes] "
    "[--allow-outside-results]";

int parse_jobs(const std::string& text) {
  std::size_t used = 0;
  int n = 0;
  try {
    n = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || n < 1 || n > 1024) {
    throw UsageError("--jobs=" + text +
                     " is not a number of runs at once; give an integer from 1 to 1024");
  }
  return n;
}

std::size_t count(const std::vector<RunRecord>& records, RunState state) {
  return static_cast<std::size_t>(std::count_if(
      records.begin(), records.end(), [&](const RunRecord& r) { return r.state == state; }));
}

std::string shown(const fs::path& p) {
  return p.lexically_normal().string();
}

/// Runs the pending runs, `jobs` at a time here; under mpirun spread over the ranks
/// (study/rank_share.hpp), each rank running `jobs_given` at a time (0: its own choice). False
/// when interrupted.
bool run_runs(std::vector<RunRecord>& records, int jobs, int jobs_given,
              const std::function<void()>& on_change) {
  study::RunnerOptions options;
  options.executable = fs::read_symlink("/proc/self/exe");
  options.jobs = jobs;
  options.progress = &std::cerr;
  if (parallel::world_size() > 1)
    return study::run_over_ranks(records, options, jobs_given, on_change);
  return study::run_pending(records, options, on_change);
}

}  // namespace

int study_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"force", "dry-run", "no-report", "yes", "allow-outside-results"},
                    {"jobs"});
  if (a.positional().size() != 1) throw UsageError(kStudyUsage);
  const int cli_jobs = a.value("jobs") ? parse_jobs(*a.value("jobs")) : 0;  // 0: not given
  const fs::path file = a.positional()[0];

  std::vector<scenario::Diagnostic> diagnostics;
  const auto doc = scenario::load_document(file, diagnostics);
  std::optional<study::StudyFile> s;
  std::vector<study::PlannedRun> runs;
  if (doc) s = study::read_study(*doc, diagnostics);
  if (s) runs = study::expand(*s, diagnostics);
  if (s && !a.flag("allow-outside-results")) {  // results inside the study file's folder
    if (auto outside = study::output_outside_folder(*s)) diagnostics.push_back(std::move(*outside));
  }
  if (!diagnostics.empty()) {
    scenario::print_diagnostics(std::cerr, doc ? &*doc : nullptr, file, diagnostics,
                                scenario::Format::kText);
    return kExitConfig;
  }

  PluginRegistry registry;
  registry.load_default_directories();
  std::vector<RunRecord> records =
      study::prepare_runs(*s, std::move(runs), registry, std::cerr, a.flag("yes"));
  const fs::path state_file = s->output / "study.json";
  const auto previous = study::read_previous_state(state_file);
  for (RunRecord& r : records) {
    if (r.state == RunState::kPending && !a.flag("force") && study::up_to_date(previous, r)) {
      r.state = RunState::kSkipped;
      r.message = "up to date";
    }
  }
  const int jobs = cli_jobs > 0 ? cli_jobs : s->jobs.value_or(std::max(1, usable_cpus() / 2));
  const std::size_t to_run = count(records, RunState::kPending);
  const std::size_t invalid = count(records, RunState::kInvalid);
  std::cerr << "study: " << s->name << ": " << records.size() << " runs: " << to_run << " to run, "
            << count(records, RunState::kSkipped) << " up to date (skipped), " << invalid
            << " not valid; " << jobs << " at a time; results in " << shown(s->output) << '\n';
  if (a.flag("dry-run")) {
    for (const RunRecord& r : records) {
      std::cout << r.run.name << ": "
                << (r.state == RunState::kPending   ? "would run"
                    : r.state == RunState::kSkipped ? "up to date (skipped)"
                                                    : r.message)
                << '\n';
    }
    return invalid == 0 ? kExitOk : kExitConfig;
  }

  const study::OutputLock lock(s->output);
  // Its runs get their own deadline (kStopGraceSeconds) and their summaries written first.
  install_interrupt_handler(4.0 * kStopGraceSeconds);
  const auto write = [&](const std::string& status) {
    study::write_state(state_file, *s, records, status, jobs);
  };
  write("running");
  const bool whole = run_runs(records, jobs, cli_jobs > 0 ? cli_jobs : s->jobs.value_or(0),
                              [&] { write("running"); });
  const std::size_t failed = count(records, RunState::kFailed) + invalid;
  const std::size_t interrupted = count(records, RunState::kInterrupted);
  write(!whole ? "interrupted" : failed + interrupted > 0 ? "failed" : "completed");
  std::cerr << "study: " << count(records, RunState::kCompleted) << " completed, "
            << count(records, RunState::kSkipped) << " up to date (skipped), " << failed
            << " failed"
            << (interrupted > 0 ? ", " + std::to_string(interrupted) + " interrupted" : "")
            << "; state in " << shown(state_file) << '\n';
  // The page a person opens first: every run that has results, failed ones flagged.
  if (whole && !a.flag("no-report")) run_plot_script("study_report.py", s->output);
  if (!whole) {
    std::cerr << "rumble: error: the study was interrupted; run it again to run what is left "
                 "(completed runs are up to date)\n";
    return kExitRunFailed;
  }
  return failed + interrupted == 0 ? kExitOk : kExitRunFailed;
}

}  // namespace rumble::cli
