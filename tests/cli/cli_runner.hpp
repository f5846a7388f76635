// Runs the rumble executable as a user would, in a scratch directory per test, and reads what
// it printed and wrote.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace rumble::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

/// How the child process starts, besides its arguments.
struct RunSetup {
  /// Read as standard input when not empty.
  std::filesystem::path stdin_file;
  /// RLIMIT_FSIZE in bytes when >= 0, with SIGXFSZ ignored: a write past it fails with EFBIG, as
  /// one on a full disk fails with ENOSPC.
  long file_size_limit = -1;
  /// Variables set in the child's environment ({"HOME", "/scratch/home"}), the rest inherited.
  std::vector<std::pair<std::string, std::string>> environment;
};

/// Runs `rumble <args>` (arguments are passed as they are, no shell) and waits.
CliResult run_rumble(const std::vector<std::string>& args, const RunSetup& setup = {});

/// Starts `rumble <args>` without waiting; returns its process id. Its stdout and stderr go to
/// `output` (created), or are discarded when it is empty.
pid_t start_rumble(const std::vector<std::string>& args, const std::filesystem::path& output = {});

/// Waits for a process started by start_rumble: its exit code, or 128 + the signal that ended it.
int wait_rumble(pid_t pid);

/// A fresh, empty directory for one test (under the build tree).
std::filesystem::path scratch_directory(const std::string& test_name);

/// A small, fast, valid scenario: single wheel on a Winkler soil, Gauss-Seidel, 0.05 s.
nlohmann::json small_scenario();

/// small_scenario() on 10 sleepers over a small FEM soil (stiff, 6 m hemisphere resolving 40 Hz
/// within 1.5 m of the track): a few thousand DOFs, seconds to mesh and run.
nlohmann::json small_fem_scenario();

/// Writes the scenario as <dir>/scenario.json and returns its path.
std::filesystem::path write_scenario(const std::filesystem::path& dir, const nlohmann::json& s);

/// Number of data rows (lines after the header) of a CSV file.
std::size_t csv_rows(const std::filesystem::path& file);

nlohmann::json read_json(const std::filesystem::path& file);

/// The numbers of a CSV file after its header line: the first column (time) in `times`, the
/// others in `values`, row by row.
void read_csv(const std::filesystem::path& file, std::vector<double>& times,
              std::vector<double>& values);

/// The whole file as text ("" when it cannot be read).
std::string file_text(const std::filesystem::path& file);

}  // namespace rumble::testing
