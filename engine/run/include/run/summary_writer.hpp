// summary.json: written when the run starts (status "running", the scenario as validated,
// versions, plugins, the process) and rewritten when it ends (status, times, peaks, files), always
// atomically (a new file renamed over it, results/new_file.hpp), so a reader never sees half a
// file. While the run goes, a heartbeat in it (the end of the last macro step, the wall clock) is
// refreshed about once a second, so a reader can tell a live run from one that died still saying
// "running". docs/scenario.md says what each status means.
#pragma once

#include <array>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "results/run_status.hpp"
#include "scenario/run_spec.hpp"

namespace rumble {

struct RunComponents;
class ResultsDirectory;

class SummaryWriter {
 public:
  /// Writes the first summary at once; later heartbeats at most every heartbeat_seconds. Throws
  /// RunError when the directory refuses it.
  SummaryWriter(ResultsDirectory& results, const scenario::RunSpec& spec,
                const RunComponents& components, double heartbeat_seconds);
  /// Sets a top-level entry of the next write.
  void set(const std::string& key, nlohmann::json value) {
    const std::lock_guard lock(mutex_);
    summary_[key] = std::move(value);
    changed_ = true;
  }
  /// After every final macro step, ending at t [s], the steps-th: rewrites summary.json with a
  /// new heartbeat when heartbeat_seconds have passed since the last write. Allocates nothing
  /// (the text around the heartbeat is kept); throws RunError when the write fails.
  void heartbeat(double t, std::size_t steps);
  /// Writes the final summary with the run's status (and why, when not completed).
  void finish(RunStatus status, const std::string& message);
  /// After an exception: status "failed" (or `status`) with the message, as far as the disk
  /// allows; never throws (the original error is the one to report).
  void fail(const std::string& message, RunStatus status = RunStatus::kFailed) noexcept;
  /// From a crash's signal handler (run/crash_record.hpp): the last summary written, with status
  /// "crashed" and "crash": {"signal", "participant"} after the last heartbeat. Async-signal-safe:
  /// it writes text kept from the last write and allocates nothing; a failing disk is ignored.
  void crashed(int sig, const char* participant) noexcept;
  /// From the stop deadline's watchdog (core/interrupt.hpp), while `phase` still runs on the
  /// run's thread: status "interrupted" with why, and nothing written after it. Never throws.
  void stopped_at_deadline(const std::string& message) noexcept;

 private:
  using Clock = std::chrono::steady_clock;
  /// {"t_s", "macro_steps", "utc", "unix_time_s"} of now into buffer; returns its length.
  std::size_t format_heartbeat(char* buffer, std::size_t size) const;
  void write();
  void write_pieces(const char* heartbeat, std::size_t length);

  // Guards what set(), heartbeat(), finish(), fail() and stopped_at_deadline() touch: the last
  // runs on the watchdog's thread. crashed() takes no lock (a signal handler).
  std::mutex mutex_;
  bool sealed_ = false;  // stopped_at_deadline wrote the last word
  std::filesystem::path path_, tmp_;
  nlohmann::json summary_;
  bool changed_ = true;           // summary_ differs from what prefix_ + suffix_ hold
  std::string prefix_, suffix_;   // summary.json before and after the heartbeat's value
  std::string crashed_suffix_;    // suffix_ with status "crashed"
  std::array<char, 192> beat_{};  // the last heartbeat written, for crashed()
  std::size_t beat_length_ = 0;
  double t_ = 0.0;  // s, end of the last final macro step
  std::size_t steps_ = 0;
  Clock::duration heartbeat_interval_;
  Clock::time_point next_heartbeat_;
};

}  // namespace rumble
