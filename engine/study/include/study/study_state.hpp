// OUTPUT/study.json: the state of every run of a study (name, patches, key, status, exit code,
// wall time, results directory) and the study's name, description and axes. Written whole and
// atomically whenever a run starts or ends, read by the next `rumble study` (what is up to date)
// and by the report. docs/study.md.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "study/expansion.hpp"
#include "study/study_file.hpp"

namespace rumble::study {

enum class RunState { kPending, kInvalid, kRunning, kCompleted, kFailed, kInterrupted, kSkipped };

/// "pending", "failed" (invalid), "running", "completed", "failed", "interrupted", "skipped".
const char* state_name(RunState state);

struct RunRecord {
  PlannedRun run;
  std::filesystem::path results;  // OUTPUT/<name>
  std::string key;                // "" when the run's scenario is not valid
  RunState state = RunState::kPending;
  std::optional<int> exit_code;
  std::optional<double> wall_time_s;
  std::string message;  // why it failed, was skipped or did not start
  /// The child's command line after the executable: run FILE --set ... --output DIR ...
  std::vector<std::string> command;
  /// Under mpirun: the rank that ran it and that rank's host (study/rank_share.hpp).
  std::optional<int> rank;
  std::string host;
};

/// What the last study.json says of a run.
struct PreviousRun {
  std::string key;
  std::string status;
};

/// name -> previous state; empty when there is no study.json or it cannot be read.
std::map<std::string, PreviousRun> read_previous_state(const std::filesystem::path& study_json);

/// Up to date: the previous study.json has this key for the run with status "completed" or
/// "skipped", and the run's summary.json says "completed".
bool up_to_date(const std::map<std::string, PreviousRun>& previous, const RunRecord& record);

/// Writes study.json (a temporary file renamed over it). `status`: "running", "completed",
/// "failed", "interrupted". Throws RunError when it cannot be written.
void write_state(const std::filesystem::path& study_json, const StudyFile& study,
                 const std::vector<RunRecord>& records, const std::string& status, int jobs);

}  // namespace rumble::study
