// A run whose process ended without a word (kill -9, a crash its handler could not record, the
// machine's power) leaves summary.json at status "running", with a heartbeat that has stopped.
// Whoever next takes its results directory's lock (a rerun, `rumble post`, the study that started
// it) knows that no process holds it any more, so it says so: the summary is rewritten with
// status "died" and a message from the last heartbeat, and the message is logged
// (docs/scenario.md, "summary.json").
#pragma once

#include <filesystem>
#include <string>

namespace rumble {

/// For a caller that holds `dir`'s lock (ResultsDirectory): when dir/summary.json says
/// "running", rewrites it as "died" and returns the message (what was reached, when, by which
/// process); "" otherwise, and when the summary cannot be read or written.
std::string settle_dead_run(const std::filesystem::path& dir) noexcept;

/// The same for a caller that holds no lock (a study whose run ended): takes the lock first, and
/// does nothing while a live process holds it.
std::string settle_dead_run_if_unlocked(const std::filesystem::path& dir) noexcept;

}  // namespace rumble
