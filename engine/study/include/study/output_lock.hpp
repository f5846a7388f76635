// One `rumble study` at a time in a study's output folder: an exclusive flock on
// OUTPUT/.rumble-study.lock holding the process id, released when the process ends.
#pragma once

#include <filesystem>

namespace rumble::study {

class OutputLock {
 public:
  /// Creates `output` when missing and locks it. Throws RunError naming the holder when another
  /// study holds it, or why the folder cannot be used.
  explicit OutputLock(const std::filesystem::path& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace rumble::study
