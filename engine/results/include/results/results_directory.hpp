// The results directory of one `rumble run`, held for the whole run (issue #8):
//   .rumble.lock           an exclusive flock for the run, holding its process id: a second run
//                          into the same directory stops at once and names the first. The kernel
//                          drops the lock when the process ends, however it ends; the file stays
//                          (empty between runs).
//   .rumble-manifest.json  the scenario file and every file and directory the run writes, each
//                          listed before it is created (a crash leaves it listed), and at the end
//                          what appeared meanwhile (plots, a plugin's own files).
// A rerun of the same scenario file removes exactly what the manifest lists before it writes. A
// directory that holds another scenario's results or files no manifest lists is refused unless
// the user says --overwrite, and even then only listed files are deleted. The directory soil_frf/
// of `rumble soil-frf` is left alone. docs/scenario.md.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace rumble {

class ResultsDirectory {
 public:
  static constexpr const char* kLockFile = ".rumble.lock";
  static constexpr const char* kManifestFile = ".rumble-manifest.json";

  /// Creates `directory` when missing, locks it, checks what it holds and removes the files the
  /// previous run listed. `scenario_file`: the run's scenario (a rerun of the same file replaces
  /// its own results); `overrides`: its --set values as "POINTER=VALUE" (part of what makes a
  /// rerun "the same": the same file with other values is another run). overwrite: also replace
  /// another scenario's results, and write beside files that no manifest lists (they are kept).
  /// Throws RunError when the directory cannot be created or locked (another run holds it),
  /// ConfigError when it holds what may not be replaced.
  ResultsDirectory(std::filesystem::path directory, const std::filesystem::path& scenario_file,
                   bool overwrite, std::vector<std::string> overrides = {});
  /// Locks the results of a finished run to add derived files to them (`rumble post`): nothing
  /// is removed, and what appears is listed at the end, so a rerun removes it with the rest. A
  /// directory with receivers.csv but no manifest is taken too while it has no post/ (the
  /// manifest then lists what is added). Throws ConfigError when `directory` holds no usable
  /// manifest (nor such a receivers.csv), RunError when it is locked.
  struct Reopen {};
  ResultsDirectory(std::filesystem::path directory, Reopen);
  /// Lists what appeared during the run (list_new_files), then releases the lock.
  ~ResultsDirectory();
  ResultsDirectory(const ResultsDirectory&) = delete;
  ResultsDirectory& operator=(const ResultsDirectory&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  /// The path of the results file `relative` ("contact.csv", "fields/soil_000001.vtu"), listed
  /// in the manifest first. Create it with open_new_file (results/new_file.hpp). Throws RunError.
  std::filesystem::path file(const std::string& relative);
  /// Creates the subdirectory `relative`, listed; a file or link with its name is replaced, never
  /// followed. Throws RunError.
  std::filesystem::path subdirectory(const std::string& relative);
  /// Lists the files that appeared since the run began and that nobody listed: the plots, a
  /// plugin's own files. Throws RunError when the manifest cannot be written.
  void list_new_files();

 private:
  struct Previous;
  void lock();
  /// Reopen without a manifest: true for a regular receivers.csv and no post/ (ConfigError when
  /// post/ stands there), false without receivers.csv.
  bool adoptable_for_post() const;
  void release() noexcept;
  Previous read_manifest() const;
  void clear_previous(bool overwrite);
  void remove_listed(const std::string& relative) const;
  void write_manifest() const;

  std::filesystem::path dir_;
  std::string scenario_;  // canonical path of the scenario; "" when it is not a regular file
  std::vector<std::string> overrides_;  // its --set values, "POINTER=VALUE"
  int lock_fd_ = -1;
  std::set<std::string> files_, directories_;              // listed, relative to dir_
  std::map<std::string, std::pair<dev_t, ino_t>> before_;  // what stood there when the run began
};

}  // namespace rumble
