// The adaptive macro step of the explicit couplers (params.adaptive, rumble/macro_steps.hpp)
// through the CLI, on the small Winkler scenario with a rail dip that the wheel reaches after
// 10 ms, the track's micro-step fixed at 25 us (it divides every macro step below), against the
// monolithic reference recorded every min_step (so every adaptive step ends on its grid):
//   - the step stays within its bounds, is a whole number of min_step, ends at time.end, is
//     recorded in interface.csv and summary.json, and is short where the wheel meets the dip;
//   - its error against the reference and its energy residual fall with the tolerance (fixed
//     steps of the same number are printed for comparison: on this scenario they are more
//     accurate, docs/couplers.md says why);
//   - inverted bounds are refused at validate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "coupler_runs.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

constexpr double kMinStep = 5e-5, kMaxStep = 2e-3;  // s
constexpr double kEnd = 0.03;                       // s

nlohmann::json dip(double H) {
  nlohmann::json s = dip_scenario(kEnd, 2.5e-5);
  s["time"]["macro_step"] = H;
  return s;
}

nlohmann::json adaptive_coupler(const std::string& type, double tolerance) {
  return {
      {"type", type},
      {"params",
       {{"adaptive", {{"min_step", kMinStep}, {"max_step", kMaxStep}, {"tolerance", tolerance}}}}}};
}

/// The monolithic reference at H = min_step (run once per test process). ctest runs each test
/// in its own process, in parallel, so the directory is named after the test that asks first:
/// two tests sharing one directory wiped each other's results (CI, stop 16).
const Histories& reference() {
  static const Histories u = [] {
    nlohmann::json s = dip(kMinStep);
    s["coupling"] = {{"type", "monolithic"}, {"params", nlohmann::json::object()}};
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    return csv(run("adaptive_reference_" + test, s) / "footprint_displacement.csv");
  }();
  return u;
}

/// interface.csv's macro step column (the 7th of 8 after t), without the t = 0 row.
std::vector<double> macro_steps(const std::filesystem::path& dir, std::vector<double>& ends) {
  const Histories h = csv(dir / "interface.csv");
  constexpr std::size_t kColumns = 8;
  std::vector<double> steps;
  ends.clear();
  for (std::size_t k = 1; k < h.times.size(); ++k) {
    steps.push_back(h.values[kColumns * k + 6]);
    ends.push_back(h.times[k]);
  }
  return steps;
}

TEST(AdaptiveStep, StaysInItsBoundsAndShortensWhereTheWheelMeetsTheDip) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("gauss_seidel", 0.05);
  const auto dir = run("adaptive_gs_bounds", s);
  std::vector<double> ends;
  const std::vector<double> steps = macro_steps(dir, ends);
  ASSERT_GT(steps.size(), 10u);
  double before = 0.0, at_dip = 1.0, shortest = 1.0, longest = 0.0;
  double t = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    t += steps[k];
    EXPECT_NEAR(ends[k], t, 1e-12);  // the recorded step is the step that ended there
    shortest = std::min(shortest, steps[k]);
    longest = std::max(longest, steps[k]);
    if (k + 1 < steps.size()) {
      EXPECT_GE(steps[k], kMinStep * (1 - 1e-9));
      EXPECT_LE(steps[k], kMaxStep * (1 + 1e-9));
      EXPECT_NEAR(steps[k] / kMinStep, std::round(steps[k] / kMinStep), 1e-6);
    }
    if (ends[k] < 0.009) before = std::max(before, steps[k]);
    if (ends[k] > 0.011 && ends[k] < 0.02) at_dip = std::min(at_dip, steps[k]);
  }
  EXPECT_NEAR(ends.back(), kEnd, 1e-12);
  std::cout << "[ measured ] " << steps.size() << " steps; longest before the dip " << before
            << " s, shortest after it " << at_dip << " s\n";
  EXPECT_GT(before, 4.0 * at_dip);
  const nlohmann::json summary = read_json(dir / "summary.json");
  const nlohmann::json& recorded = summary["coupling"]["macro_step_s"];
  EXPECT_NEAR(recorded["shortest"].get<double>(), shortest, 1e-12);  // CSV: 12 digits
  EXPECT_NEAR(recorded["longest"].get<double>(), longest, 1e-12);
}

TEST(AdaptiveStep, ErrorAndEnergyResidualFallWithTheTolerance) {
  std::vector<double> errors, residuals;
  std::vector<std::size_t> counts;
  for (double tolerance : {0.2, 0.05, 0.0125}) {
    nlohmann::json s = dip(1e-3);
    s["coupling"] = adaptive_coupler("gauss_seidel", tolerance);
    const auto dir = run("adaptive_gs_" + std::to_string(static_cast<int>(1e4 * tolerance)), s);
    errors.push_back(relative_error(csv(dir / "footprint_displacement.csv"), reference()));
    residuals.push_back(
        std::abs(read_json(dir / "summary.json")["interface"]["energy_residual_J"].get<double>()));
    std::vector<double> ends;
    counts.push_back(macro_steps(dir, ends).size());
  }
  // For comparison (not a claim): fixed steps about as many as the middle tolerance took.
  const double fixed_step = std::round(kEnd / static_cast<double>(counts[1]) / kMinStep) * kMinStep;
  nlohmann::json s = dip(fixed_step);
  s["coupling"] = {{"type", "gauss_seidel"}, {"params", nlohmann::json::object()}};
  const auto fixed_dir = run("adaptive_gs_fixed", s);
  std::cout << "[ measured ] tolerance 0.2 / 0.05 / 0.0125: error " << errors[0] << " / "
            << errors[1] << " / " << errors[2] << ", energy residual " << residuals[0] << " / "
            << residuals[1] << " / " << residuals[2] << " J in " << counts[0] << " / " << counts[1]
            << " / " << counts[2] << " steps; fixed steps of " << fixed_step << " s: error "
            << relative_error(csv(fixed_dir / "footprint_displacement.csv"), reference())
            << ", energy residual "
            << read_json(fixed_dir / "summary.json")["interface"]["energy_residual_J"] << " J\n";
  // A first-order scheme: the step, and so both errors, about proportional to the tolerance
  // (measured 0.092 / 0.033 / 0.0081 and 0.69 / 0.22 / 0.062 J: 2.8x and 4x, 3.2x and 3.6x per
  // 4x tolerance). At least 2x per 4x, and more steps for a tighter tolerance.
  EXPECT_GT(errors[0] / errors[1], 2.0);
  EXPECT_GT(errors[1] / errors[2], 2.0);
  EXPECT_GT(residuals[0] / residuals[1], 2.0);
  EXPECT_GT(residuals[1] / residuals[2], 2.0);
  EXPECT_LT(counts[0], counts[1]);
  EXPECT_LT(counts[1], counts[2]);
}

TEST(AdaptiveStep, JacobiAdaptsToo) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("jacobi", 0.05);
  const auto dir = run("adaptive_jacobi", s);
  std::vector<double> ends;
  const std::vector<double> steps = macro_steps(dir, ends);
  const double error = relative_error(csv(dir / "footprint_displacement.csv"), reference());
  std::cout << "[ measured ] jacobi: " << steps.size() << " steps, error " << error << "\n";
  EXPECT_NEAR(ends.back(), kEnd, 1e-12);
  const double shortest = *std::min_element(steps.begin(), steps.end() - 1);
  EXPECT_LT(shortest, 0.25 * kMaxStep);
  EXPECT_GT(*std::max_element(steps.begin(), steps.end()), 2.0 * shortest);  // it does vary
  // Of the order of gauss_seidel's at the same tolerance (0.033); measured 0.0061.
  EXPECT_LT(error, 0.05);
}

TEST(AdaptiveStep, InvertedBoundsAreRefusedAtValidate) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("gauss_seidel", 0.05);
  s["coupling"]["params"]["adaptive"]["min_step"] = 1e-3;
  s["coupling"]["params"]["adaptive"]["max_step"] = 1e-4;
  const auto dir = scratch_directory("adaptive_inverted");
  const CliResult r = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("/coupling"));
  EXPECT_THAT(r.output, HasSubstr("min_step 0.001 s is longer than max_step 0.0001 s"));
  EXPECT_THAT(r.output, HasSubstr("give min_step <= max_step"));
}

}  // namespace
}  // namespace rumble::testing
