#include "run/csv_file.hpp"

#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace rumble {

CsvFile::CsvFile(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : path_(path), n_values_(columns.empty() ? 0 : columns.size() - 1) {
  file_ = std::fopen(path.c_str(), "w");
  check(file_ != nullptr);
  for (std::size_t i = 0; i < columns.size(); ++i)
    check(std::fprintf(file_, "%s%s", i == 0 ? "" : ",", columns[i].c_str()) >= 0);
  check(std::fputc('\n', file_) != EOF && std::fflush(file_) == 0);
}

CsvFile::~CsvFile() {
  if (file_ != nullptr) std::fclose(file_);
}

void CsvFile::row(double t, const double* values, std::size_t n) {
  if (n != n_values_) {
    throw RunError(path_.string() + ": row of " + std::to_string(n) + " values, header has " +
                   std::to_string(n_values_));
  }
  bool ok = std::fprintf(file_, "%.9g", t) >= 0;
  for (std::size_t i = 0; i < n && ok; ++i) ok = std::fprintf(file_, ",%.9g", values[i]) >= 0;
  check(ok && std::fputc('\n', file_) != EOF && std::fflush(file_) == 0);
}

void CsvFile::check(bool ok) const {
  if (ok) return;
  const int err = errno;
  throw RunError("cannot write results file " + path_.string() + ": " + std::strerror(err) +
                 (err == ENOSPC ? "; free disk space or set outputs.directory to another disk"
                                : "; check that outputs.directory is writable"));
}

}  // namespace rumble
