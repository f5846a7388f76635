// Runs a study's runs as child processes of the rumble executable, at most `jobs` at once, each
// child's output in its results directory (run.log), a crash of one never the study's. Progress
// on a stream: a line per run started and ended, with "k of n done" and an ETA from the mean wall
// time of the runs that ended. Ctrl-C (interrupt_requested) stops starting runs and forwards
// SIGINT to the running ones, which stop cleanly. docs/study.md.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <vector>

#include "study/study_state.hpp"

namespace rumble::study {

struct RunnerOptions {
  std::filesystem::path executable;  // what each child runs: this rumble
  int jobs = 1;
  std::ostream* progress = nullptr;  // one line per event; null: silent
  double poll_seconds = 0.05;        // how often children are checked
};

/// Runs every record in state kPending (command filled), updating state, exit code, wall time
/// and message; calls on_change after every start and end (to write study.json). Returns false
/// when interrupted: then every run that did not start is kInterrupted.
bool run_pending(std::vector<RunRecord>& records, const RunnerOptions& options,
                 const std::function<void()>& on_change);

/// "0.4 s", "12 s", "3 min 05 s", "2 h 04 min".
std::string duration_text(double seconds);

}  // namespace rumble::study
