// Runs of a scenario through the CLI and their recorded histories, for comparing couplers.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace rumble::testing {

/// small_scenario() with a 0.5 mm dip 0.5 m long that the wheel reaches after 10 ms, run for
/// `end` [s]; `micro_step` [s] fixes the track's micro-step (0: the default, which depends on H).
inline nlohmann::json dip_scenario(double end, double micro_step = 0.0) {
  nlohmann::json s = small_scenario();
  s["time"]["end"] = end;
  s["track"]["unevenness"] = {
      {"type", "dip"}, {"position", 3.45}, {"length", 0.5}, {"depth", 5e-4}};
  if (micro_step > 0.0) s["track"]["integrator"] = {{"micro_step", micro_step}};
  return s;
}

/// One results file: the time column and the other columns row after row.
struct Histories {
  std::vector<double> times, values;
};

inline Histories csv(const std::filesystem::path& file) {
  Histories h;
  read_csv(file, h.times, h.values);
  return h;
}

/// Runs the scenario in a scratch directory named `name`; returns its results directory.
inline std::filesystem::path run(const std::string& name, const nlohmann::json& scenario) {
  const auto dir = scratch_directory(name);
  const CliResult r = run_rumble({"run", write_scenario(dir, scenario).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir / "results";
}

/// Largest |a - b| over histories recorded at the same times.
inline double largest_difference(const Histories& a, const Histories& b) {
  EXPECT_EQ(a.times, b.times);
  EXPECT_EQ(a.values.size(), b.values.size());
  double d = 0.0;
  for (std::size_t k = 0; k < std::min(a.values.size(), b.values.size()); ++k)
    d = std::max(d, std::abs(a.values[k] - b.values[k]));
  return d;
}

/// Largest |a - reference| over the times both recorded, relative to the largest
/// |reference - reference at t = 0| (the dynamic part of the motion). Every time of the coarser
/// of the two runs must be on the other's grid (one run's steps may be finer, or vary).
inline double relative_error(const Histories& a, const Histories& reference) {
  const std::size_t width = reference.values.size() / reference.times.size();
  std::map<long long, std::size_t> row_at;  // time in ns -> row of a
  for (std::size_t k = 0; k < a.times.size(); ++k) row_at[std::llround(a.times[k] * 1e9)] = k;
  double error = 0.0, scale = 0.0;
  std::size_t compared = 0;
  for (std::size_t k = 0; k < reference.times.size(); ++k) {
    for (std::size_t j = 0; j < width; ++j)
      scale = std::max(scale, std::abs(reference.values[k * width + j] - reference.values[j]));
    const auto it = row_at.find(std::llround(reference.times[k] * 1e9));
    if (it == row_at.end()) continue;
    ++compared;
    for (std::size_t j = 0; j < width; ++j) {
      error = std::max(
          error, std::abs(a.values[it->second * width + j] - reference.values[k * width + j]));
    }
  }
  EXPECT_EQ(compared, std::min(a.times.size(), reference.times.size()))
      << "the runs do not share a time grid";
  return error / scale;
}

}  // namespace rumble::testing
