// summary.json: written when the run starts (status "running", the scenario as validated,
// versions, plugins) and rewritten when it ends (status, times, peaks, files), always atomically
// (a new file renamed over it, run/new_file.hpp), so a reader never sees half a file.
// docs/scenario.md says what each status means.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "scenario/run_spec.hpp"

namespace rumble {

struct RunComponents;
class ResultsDirectory;

enum class RunStatus { kRunning, kCompleted, kInterrupted, kFailed };

/// "running", "completed", "interrupted", "failed" (as summary.json spells them).
const char* status_name(RunStatus status);
/// The process exit code of a run that ended so: 0 completed, 3 otherwise (exit_codes.hpp).
int exit_code(RunStatus status);

class SummaryWriter {
 public:
  /// Writes the first summary at once. Throws RunError when the directory refuses it.
  SummaryWriter(ResultsDirectory& results, const scenario::RunSpec& spec,
                const RunComponents& components);
  /// Sets a top-level entry of the next write.
  void set(const std::string& key, nlohmann::json value) { summary_[key] = std::move(value); }
  /// Writes the final summary with the run's status (and why, when not completed).
  void finish(RunStatus status, const std::string& message);
  /// After an exception: status "failed" with the message, as far as the disk allows; never
  /// throws (the original error is the one to report).
  void fail(const std::string& message) noexcept;

 private:
  void write() const;
  std::filesystem::path path_, tmp_;
  nlohmann::json summary_;
};

}  // namespace rumble
