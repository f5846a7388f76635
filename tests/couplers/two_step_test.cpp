// The two_step coupler through the CLI, on the small Winkler scenario of tests/cli (20 sleepers,
// one wheel at 20 m/s, 1 ms macro steps) with a rail-joint dip under the wheel's path:
//   - with the reduced soil equal to the soil, step 2 reproduces step 1's soil motion exactly,
//     and the whole run equals gauss_seidel with the same input waveforms (an independent
//     scheme that couples the track to that soil directly);
//   - with a different reduced soil the track's results are those of gauss_seidel on the
//     reduced soil, the soil's are its response to those forces, and the mismatch is reported;
//   - every participant's files have a row per macro step;
//   - no reduced soil: validate says what to add.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "coupler_runs.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

nlohmann::json winkler(double k) {
  return {{"type", "winkler"}, {"params", {{"k", k}, {"c", 2e5}}}};
}

nlohmann::json two_step(const nlohmann::json& reduced_soil) {
  return {{"type", "two_step"},
          {"params", nlohmann::json::object()},
          {"participants", {{"reduced_soil", reduced_soil}}}};
}

TEST(TwoStep, SameSoilInBothStepsEqualsGaussSeidel) {
  nlohmann::json s = dip_scenario(0.03);
  s["coupling"] = {{"type", "gauss_seidel"}, {"params", {{"interpolation", 1}}}};
  const auto gs = run("two_step_same_gs", s);
  s["coupling"] = two_step(s["soil"]);
  const auto ts = run("two_step_same", s);
  // Both steps feed the soil the same waveforms in the same order of operations as
  // gauss_seidel (track first, order-0 extrapolation, linear forces), so the histories differ
  // only by the soils' static states: the track's static iteration (on the reduced soil here, on
  // the soil in gauss_seidel) stops at a relative change of 1e-9, and the soil of step 2 starts
  // from its final forces. Bound: 1e-8 of the largest displacement (measured: 1.1e-10).
  const Histories u = csv(ts / "footprint_displacement.csv");
  const double scale = *std::max_element(u.values.begin(), u.values.end());
  EXPECT_LT(largest_difference(u, csv(ts / "reduced_soil_footprint_displacement.csv")),
            1e-8 * scale);
  EXPECT_LT(largest_difference(u, csv(gs / "footprint_displacement.csv")), 1e-8 * scale);
  EXPECT_EQ(largest_difference(csv(ts / "contact.csv"), csv(gs / "contact.csv")), 0.0);
  EXPECT_EQ(largest_difference(csv(ts / "footprint_force.csv"), csv(gs / "footprint_force.csv")),
            0.0);
  const nlohmann::json summary = read_json(ts / "summary.json");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_LT(
      summary["interface"]["max_relative_residual_by_group"]["footprint_displacement mismatch"]
          .get<double>(),
      1e-8);
  EXPECT_EQ(summary["time"]["macro_steps"], 30);
  // Every report of a two-step is final for some participants only: 30 of step 1, 30 of step 2.
  EXPECT_EQ(summary["coupling"]["partial_step_reports"], 60);
  EXPECT_EQ(summary["coupling"]["iterations"]["mean_per_step"], 1.0);
}

TEST(TwoStep, TrackRunsOnTheReducedSoilAndTheSoilFollowsItsForces) {
  nlohmann::json s = dip_scenario(0.03);
  s["soil"] = winkler(1e8);
  s["coupling"] = {{"type", "gauss_seidel"}, {"params", {{"interpolation", 1}}}};
  s["soil"] = winkler(2e8);  // the reduced soil alone, coupled directly
  const auto on_reduced = run("two_step_reduced_gs", s);
  s["soil"] = winkler(1e8);
  s["coupling"] = two_step(winkler(2e8));
  const auto ts = run("two_step_stiffer_reduced", s);
  EXPECT_EQ(largest_difference(csv(ts / "contact.csv"), csv(on_reduced / "contact.csv")), 0.0);
  EXPECT_EQ(largest_difference(csv(ts / "reduced_soil_footprint_displacement.csv"),
                               csv(on_reduced / "footprint_displacement.csv")),
            0.0);
  // The soil is half as stiff: under (nearly) the same forces its static displacement doubles,
  // so the mismatch relative to its own largest displacement is about one half. Bounds: the
  // dynamic part and the dashpots move it by a few percent.
  const nlohmann::json summary = read_json(ts / "summary.json");
  const double mismatch =
      summary["interface"]["max_relative_residual_by_group"]["footprint_displacement mismatch"]
          .get<double>();
  EXPECT_GT(mismatch, 0.4);
  EXPECT_LT(mismatch, 0.6);
  // Row per macro step (and the initial state) in every participant's files.
  for (const char* f : {"contact.csv", "footprint_force.csv", "footprint_displacement.csv",
                        "interface.csv", "reduced_soil_footprint_velocity.csv"})
    EXPECT_EQ(csv_rows(ts / f), 31u) << f;
}

TEST(TwoStep, WithoutAReducedSoilValidateSaysWhatToAdd) {
  nlohmann::json s = dip_scenario(0.03);
  s["coupling"] = {{"type", "two_step"}, {"params", nlohmann::json::object()}};
  const auto dir = scratch_directory("two_step_no_reduced_soil");
  const CliResult r = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("reduced_soil"));
  EXPECT_THAT(r.output, HasSubstr("/coupling/participants/reduced_soil"));
}

}  // namespace
}  // namespace rumble::testing
