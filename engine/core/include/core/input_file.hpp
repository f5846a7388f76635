// Files a command reads as input (scenario and study files, a run's results for `rumble post`,
// manifests, logs, plugin libraries) are checked to be regular files of bounded size before they
// are opened: opening a FIFO waits for a writer for ever, and a device such as /dev/zero never
// ends (docs/scenario.md, "Limits").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace rumble {

/// Largest JSON file that a command reads back from what rumble wrote (summary.json, a results
/// manifest, a study's state) [bytes]: they hold tens of kB per thousand receivers or runs.
inline constexpr std::uintmax_t kMaxResultJsonBytes = std::uintmax_t{64} << 20;
/// Largest results CSV that `rumble post` reads whole [bytes]: receivers.csv of 2e4 receivers
/// for 2e4 samples; what it parses takes about half its size in memory.
inline constexpr std::uintmax_t kMaxResultCsvBytes = std::uintmax_t{4} << 30;

/// "a directory", "a FIFO (named pipe)", "a device", "a socket", "not a file": what a path that
/// is not a regular file is, for messages.
std::string file_kind(const std::filesystem::file_status& status);

/// Why `path` (links followed) cannot be read as an input of at most max_bytes: "does not
/// exist", "is a FIFO (named pipe), not a regular file", "is 5.2e+09 bytes, more than the
/// 4.29e+09 that ... reads"; "" when it can.
std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes);

/// The whole of an input file; std::runtime_error "'<path>' <problem>" when
/// input_file_problem() has one, or when it cannot be read.
std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

}  // namespace rumble
