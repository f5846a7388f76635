#include "post/time_series.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/input_file.hpp"
#include "core/number_text.hpp"

namespace rumble::post {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// A number as the engine prints it (%.9g: also "nan", "inf", "-inf"); from_chars ignores the
// locale, unlike strtod.
bool parse_number(const std::string& field, double& out) {
  const std::string f = trim(field);
  if (f.empty()) return false;
  const char* first = f.data();
  const char* last = f.data() + f.size();
  if (*first == '+') ++first;  // from_chars takes no leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

}  // namespace

UniformGrid uniform_grid(std::span<const double> time, const std::string& what,
                         double max_step_ratio) {
  const std::size_t n = time.size();
  if (n < 2)
    throw std::runtime_error(what + ": " + std::to_string(n) +
                             " time sample(s); post-processing needs at least 2. Run longer "
                             "(time.end) or record more often (outputs.receiver_interval)");
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (!std::isfinite(time[i]) || !std::isfinite(time[i + 1]) || !(time[i + 1] > time[i]))
      throw std::runtime_error(what + ": time is not strictly increasing at data row " +
                               std::to_string(i + 2) + " (t = " + number_text(time[i], 9) +
                               " s, then " + number_text(time[i + 1], 9) +
                               " s); the file is damaged or two runs wrote into it. Rerun the "
                               "scenario into a fresh results directory");
  }
  UniformGrid grid;
  grid.t0 = time[0];
  const double dt_mean = (time[n - 1] - time[0]) / static_cast<double>(n - 1);
  bool uniform = true;
  for (std::size_t i = 0; i < n && uniform; ++i)
    uniform = std::abs(time[i] - (time[0] + static_cast<double>(i) * dt_mean)) <= 0.01 * dt_mean;
  if (uniform) {
    grid.dt = dt_mean;
    grid.count = n;
    return grid;
  }
  std::vector<double> steps(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) steps[i] = time[i + 1] - time[i];
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double median = sorted[sorted.size() / 2];
  const auto longest = std::max_element(steps.begin(), steps.end());
  if (*longest > max_step_ratio * median) {
    const auto row = static_cast<std::size_t>(longest - steps.begin()) + 2;
    throw std::runtime_error(
        what + ": the time step varies too much to resample: the step of " +
        number_text(*longest, 9) + " s to data row " + std::to_string(row) +
        " (t = " + number_text(time[row - 1], 9) + " s) is " + number_text(*longest / median, 9) +
        " times the median step " + number_text(median, 9) +
        " s (allowed: " + number_text(max_step_ratio, 9) +
        "). Record receivers at a fixed interval (outputs.receiver_interval) or post-process "
        "the part of the record before the gap");
  }
  grid.dt = median;
  grid.count = static_cast<std::size_t>(std::floor((time[n - 1] - time[0]) / median + 1e-9)) + 1;
  grid.resampled = true;
  return grid;
}

TimeSeries on_grid(std::span<const double> time, std::span<const double> values,
                   const UniformGrid& grid) {
  if (time.size() != values.size())
    throw std::invalid_argument("on_grid: " + std::to_string(time.size()) + " times but " +
                                std::to_string(values.size()) + " values");
  TimeSeries out;
  out.t0 = grid.t0;
  out.dt = grid.dt;
  if (!grid.resampled) {
    out.values.assign(values.begin(), values.end());
    out.values.resize(grid.count, 0.0);
    return out;
  }
  out.values.resize(grid.count);
  std::size_t j = 0;  // time[j] <= t < time[j + 1]
  for (std::size_t k = 0; k < grid.count; ++k) {
    const double t = out.time(k);
    while (j + 2 < time.size() && time[j + 1] <= t) ++j;
    const double h = time[j + 1] - time[j];
    const double w = std::clamp((t - time[j]) / h, 0.0, 1.0);
    out.values[k] = (1.0 - w) * values[j] + w * values[j + 1];
  }
  return out;
}

TimeSeries resample_uniform(std::span<const double> time, std::span<const double> values,
                            const std::string& what, double max_step_ratio) {
  return on_grid(time, values, uniform_grid(time, what, max_step_ratio));
}

std::optional<std::size_t> CsvTable::find(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<std::size_t>(it - names.begin());
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(field);
      field.clear();
    } else if (c != '\r') {
      field += c;
    }
  }
  fields.push_back(field);
  return fields;
}

CsvTable read_csv(const std::filesystem::path& path) {
  const std::string problem = input_file_problem(path, kMaxResultCsvBytes);
  if (problem == "does not exist")
    throw std::runtime_error("cannot read " + path.string() +
                             ": no such file or not readable. Check the results directory (it "
                             "is the run's outputs.directory) and rerun the scenario if the "
                             "file was never written");
  if (!problem.empty())
    throw std::runtime_error(path.string() + " " + problem +
                             ": rumble post reads the CSV files a run wrote, regular files of at "
                             "most 4 GiB (docs/post-processing.md)");
  const std::string text = read_input_file(path, kMaxResultCsvBytes);
  CsvTable table;
  table.path = path;
  std::istringstream lines(text);
  std::string line;
  if (!std::getline(lines, line) || trim(line).empty())
    throw std::runtime_error(path.string() +
                             " is empty: the run stopped before recording anything. Rerun the "
                             "scenario");
  std::vector<std::string> header = split_csv_line(line);
  for (std::string& h : header) h = trim(h);
  if (header.front() != "t [s]")
    throw std::runtime_error(path.string() + ": first header field is '" + header.front() +
                             "', expected 't [s]'; this is not a results CSV written by rumble");
  table.names.assign(header.begin() + 1, header.end());
  table.columns.assign(table.names.size(), {});
  const bool ends_with_newline = !text.empty() && text.back() == '\n';
  std::size_t line_no = 1;
  while (std::getline(lines, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const std::vector<std::string> fields = split_csv_line(line);
    const bool last = lines.peek() == std::char_traits<char>::eof();
    if (fields.size() != header.size()) {
      if (last && !ends_with_newline) {
        table.warnings.push_back(path.filename().string() + ": dropped the cut last line " +
                                 std::to_string(line_no) + " (" + std::to_string(fields.size()) +
                                 " of " + std::to_string(header.size()) + " fields)");
        break;
      }
      throw std::runtime_error(path.string() + ":" + std::to_string(line_no) + ": " +
                               std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(header.size()) +
                               "; the file is damaged. Rerun the scenario");
    }
    double t = 0.0;
    std::vector<double> row(fields.size() - 1);
    bool ok = parse_number(fields[0], t);
    std::size_t bad = 0;
    for (std::size_t c = 1; c < fields.size() && ok; ++c) {
      ok = parse_number(fields[c], row[c - 1]);
      if (!ok) bad = c;
    }
    if (!ok) {
      if (last && !ends_with_newline) {
        table.warnings.push_back(path.filename().string() + ": dropped the cut last line " +
                                 std::to_string(line_no));
        break;
      }
      throw std::runtime_error(path.string() + ":" + std::to_string(line_no) + ": field " +
                               std::to_string(bad + 1) + " ('" + trim(fields[bad]) +
                               "') is not a number; the file is damaged. Rerun the scenario");
    }
    table.time.push_back(t);
    for (std::size_t c = 0; c < row.size(); ++c) table.columns[c].push_back(row[c]);
  }
  return table;
}

}  // namespace rumble::post
