#include "results/csv_file.hpp"

#include <unistd.h>

#include <cerrno>

#include "core/errors.hpp"
#include "results/new_file.hpp"

namespace rumble {

CsvFile::CsvFile(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : path_(path), n_values_(columns.empty() ? 0 : columns.size() - 1) {
  const int fd = open_new_file(path);  // never through a link standing at the name
  file_ = ::fdopen(fd, "w");
  if (file_ == nullptr) ::close(fd);
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
  if (!ok) throw RunError(write_error(path_, errno));
}

}  // namespace rumble
