// The results directory of one `rumble run`, held for the whole run, plots included (issue #8):
//   .rumble.lock   an exclusive flock for the run, holding its process id: a second run into
//                  the same directory stops at once and names the first. The kernel drops the
//                  lock when the process ends, however it ends; the file stays (empty between
//                  runs).
#pragma once

#include <filesystem>

namespace rumble {

class ResultsDirectory {
 public:
  static constexpr const char* kLockFile = ".rumble.lock";

  /// Creates `directory` when missing and locks it. Throws RunError when it cannot be created or
  /// locked (another run holds it: the message names its process id).
  explicit ResultsDirectory(std::filesystem::path directory);
  /// Releases the lock.
  ~ResultsDirectory();
  ResultsDirectory(const ResultsDirectory&) = delete;
  ResultsDirectory& operator=(const ResultsDirectory&) = delete;

  const std::filesystem::path& path() const { return dir_; }

 private:
  void lock();

  std::filesystem::path dir_;
  int lock_fd_ = -1;
};

}  // namespace rumble
