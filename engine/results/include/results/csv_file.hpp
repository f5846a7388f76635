// One CSV time history, written row by row and flushed, so that a crash or Ctrl-C keeps every
// row already recorded. It is a new file (results/new_file.hpp): whatever had its name, a symbolic
// link included, is removed, never followed. Write errors (full disk, removed directory) throw
// RunError naming the file, the system's reason and a fix.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace rumble {

class CsvFile {
 public:
  CsvFile(const std::filesystem::path& path, const std::vector<std::string>& columns);
  ~CsvFile();
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  /// Appends one row: t, then values (n must equal the number of columns - 1).
  void row(double t, const double* values, std::size_t n);
  const std::filesystem::path& path() const { return path_; }

 private:
  void check(bool ok) const;
  std::filesystem::path path_;
  std::size_t n_values_ = 0;
  std::FILE* file_ = nullptr;
  std::string line_;  // one row's text, reused
};

}  // namespace rumble
