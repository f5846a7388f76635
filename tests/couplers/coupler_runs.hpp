// Runs of a scenario through the CLI and their recorded histories, for comparing couplers.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
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

}  // namespace rumble::testing
