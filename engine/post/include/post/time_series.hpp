// Time histories as the post-processing sees them: a uniformly sampled signal (t0, dt, values),
// the resampling of a recorded time column onto such a grid, and the reading of a results CSV
// (engine/results/src/csv_file.cpp writes them: a header row of column names, the first "t [s]",
// then one row per sample, numbers printed with %.9g, "nan"/"inf" included).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rumble::post {

/// A uniformly sampled signal: values[k] is the value at t0 + k dt.
struct TimeSeries {
  double t0 = 0.0;             // s
  double dt = 0.0;             // s, > 0
  std::vector<double> values;  // the quantity's unit (m/s for velocities)

  std::size_t size() const { return values.size(); }
  double time(std::size_t k) const { return t0 + static_cast<double>(k) * dt; }
  /// Length of the record, n dt [s] (each sample stands for one step).
  double duration() const { return static_cast<double>(values.size()) * dt; }
};

/// The uniform grid a recorded time column is brought onto.
struct UniformGrid {
  double t0 = 0.0;         // s, the first recorded time
  double dt = 0.0;         // s
  std::size_t count = 0;   // samples on the grid
  bool resampled = false;  // false: the recorded times already are this grid (to 1 % of dt)
};

/// Decides the uniform grid for a recorded time column (strictly increasing, >= 2 samples).
/// When every recorded time lies within 1 % of a step from t0 + k dt with dt = (t_last - t0) /
/// (n - 1), the record is taken as it is (the CSV's 9 significant digits round times by far less
/// than that). Otherwise the grid step is the median recorded step and the values will be
/// linearly interpolated onto it; a step longer than max_step_ratio median steps (a gap that
/// interpolation would fill with a straight line) is an error. `what` names the source in
/// messages ("receivers.csv in results/x").
UniformGrid uniform_grid(std::span<const double> time, const std::string& what,
                         double max_step_ratio = 4.0);

/// The values recorded at `time` on `grid`: copied when the grid is the record's own, else
/// linearly interpolated between the recorded samples.
TimeSeries on_grid(std::span<const double> time, std::span<const double> values,
                   const UniformGrid& grid);

/// uniform_grid then on_grid, for a single column.
TimeSeries resample_uniform(std::span<const double> time, std::span<const double> values,
                            const std::string& what, double max_step_ratio = 4.0);

/// A results CSV in columns. The time column is kept apart; names are the other columns' header
/// fields, unquoted.
struct CsvTable {
  std::filesystem::path path;
  std::vector<double> time;                  // s
  std::vector<std::string> names;            // header without the time column
  std::vector<std::vector<double>> columns;  // columns[c][row]
  std::vector<std::string> warnings;         // what was tolerated (a cut last line)

  std::optional<std::size_t> find(const std::string& name) const;
};

/// Reads a results CSV. The header's fields may be plain or double-quoted ("" inside quotes is
/// one quote); the first must be "t [s]". A last line without its newline and with too few
/// fields (a run killed mid-write) is dropped with a warning; any other malformed line, a
/// missing file or an empty one throws std::runtime_error naming the file and line.
CsvTable read_csv(const std::filesystem::path& path);

/// Splits one CSV line into fields (RFC 4180 quoting, no embedded newlines).
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace rumble::post
