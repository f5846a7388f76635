#include "results/csv_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>

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
  // std::to_chars with 9 significant digits writes what printf's "%.9g" writes, at a few times
  // its speed (bench/results/csv_bench.cpp): the row is serial work in every macro step.
  constexpr std::size_t kMaxValueChars = 24;  // ",-1.23456789e-308"
  line_.resize((n + 1) * kMaxValueChars + 1);
  char* out = line_.data();
  char* const end = line_.data() + line_.size();
  for (std::size_t i = 0; i <= n; ++i) {
    if (i > 0) *out++ = ',';
    out = std::to_chars(out, end, i == 0 ? t : values[i - 1], std::chars_format::general, 9).ptr;
  }
  *out++ = '\n';
  const auto size = static_cast<std::size_t>(out - line_.data());
  check(std::fwrite(line_.data(), 1, size, file_) == size && std::fflush(file_) == 0);
}

void CsvFile::check(bool ok) const {
  if (!ok) throw RunError(write_error(path_, errno));
}

}  // namespace rumble
