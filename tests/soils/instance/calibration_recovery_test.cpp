// Calibration recovers known parameters. A synthetic target (the model itself with known
// params) is fitted from a perturbed start: the misfit has an exact zero at the true params, so
// Levenberg-Marquardt must return them with a residual at round-off. The band (1-100 Hz, the
// driving point and two transfer terms) sees every parameter: at 100 Hz the clm's mass term
// w^2 m_f = 1.2e8 N/m is of the order of its springs, its dashpots w c ~ 1e8 N/m too.
// Tolerance 1e-3 relative on each parameter (the brief's): at a residual of ~1e-9 the fitted
// log-parameters are within ~1e-8 of the truth (the Jacobian's smallest singular value ~0.1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../../cli/cli_runner.hpp"
#include "analysis/calibrate.hpp"
#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

void expect_recovered(const nlohmann::json& fitted, const nlohmann::json& truth,
                      const nlohmann::json& start) {
  for (const auto& [key, value] : truth.items()) {
    const double got = fitted.at(key).get<double>(), want = value.get<double>();
    std::printf("  %-4s start %.4e -> fitted %.6e (true %.6e, relative error %.1e)\n", key.c_str(),
                start.at(key).get<double>(), got, want, std::abs(got / want - 1.0));
    EXPECT_NEAR(got / want, 1.0, 1e-3) << key;
  }
}

TEST(SoilCalibration, EngineCalibrateRecoversTheFiveClmParameters) {
  const nlohmann::json truth = {
      {"m_f", 300.0}, {"k_f", 9.6e7}, {"c_f", 1.5e5}, {"k_c", 1.04e8}, {"c_c", 1.6e5}};
  // Every parameter off by 30 to 60 %, in both directions.
  const nlohmann::json start = {
      {"m_f", 450.0}, {"k_f", 6.0e7}, {"c_f", 2.2e5}, {"k_c", 0.7e8}, {"c_c", 2.5e5}};
  const auto layout = sleeper_row(9);
  auto target = make_soil("clm", truth, layout);

  CalibrationProblem problem;
  problem.model = &soil_type("clm");
  problem.base_params = start;
  problem.fit = {"m_f", "k_f", "c_f", "k_c", "c_c"};
  problem.layout = layout;
  problem.scenario_dir = ".";
  ASSERT_TRUE(soil_frf(*target, layout.size(), log_frequencies(1.0, 100.0, 40), 2, problem.target));
  ASSERT_EQ(problem.target.receptance.size(), 3u);  // driving point and 2 transfer terms

  const CalibrationResult result = calibrate(problem);
  std::printf("  clm: %d iterations, relative RMS residual %.2e\n", result.iterations,
              result.relative_rms);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(result.relative_rms, 1e-6);  // the start's misfit is O(1)
  EXPECT_GT(receptance_misfit(problem, start), 0.1);
  expect_recovered(result.params, truth, start);
}

// The same through the CLI, for winkler's two parameters: the target scenario's soil is a
// winkler with known k and c; `rumble calibrate` starts from other values.
TEST(SoilCalibration, CliCalibrateRecoversWinklersTwoParameters) {
  namespace t = rumble::testing;
  const auto dir = t::scratch_directory("soil_calibrate_winkler");
  nlohmann::json scenario = t::small_scenario();
  const nlohmann::json truth = {{"k", 1.3e8}, {"c", 2.5e5}};
  scenario["soil"] = {{"type", "winkler"}, {"params", truth}};
  const nlohmann::json start = {{"k", 2.6e8}, {"c", 1.0e5}};
  const auto result_file = dir / "calibration.json";
  const t::CliResult r =
      t::run_rumble({"calibrate", t::write_scenario(dir, scenario).string(), "--model", "winkler",
                     "--params", start.dump(), "--output", result_file.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json report = t::read_json(result_file);
  EXPECT_EQ(report.at("fitted"), nlohmann::json({"c", "k"}));  // every positive start value
  EXPECT_TRUE(report.at("converged").get<bool>());
  EXPECT_LT(report.at("relative_rms_residual").get<double>(), 1e-6);
  std::printf("  winkler: %d iterations, relative RMS residual %.2e\n",
              report.at("iterations").get<int>(), report.at("relative_rms_residual").get<double>());
  expect_recovered(report.at("params"), truth, start);
}

// Across models: the clm calibrated from soil properties gives its loaded footprint exactly the
// single footing's impedance K_z + i w C_z (C = (C_z / K_z) K, docs/soils.md §4), so a winkler
// fitted to the clm's driving point alone (--terms 0) must land on Gazetas' K_z and Lysmer's C_z
// of the same soil: 2.2228e8 N/m and 3.4237e5 N s/m for the medium one. The 20-footprint row of
// small_scenario() changes the middle one's compliance by ~r^18 = 5e-8 (its ends), hence 1e-6.
TEST(SoilCalibration, WinklerFittedToTheClmDrivingPointIsTheSingleFooting) {
  namespace t = rumble::testing;
  const auto dir = t::scratch_directory("soil_calibrate_winkler_on_clm");
  nlohmann::json scenario = t::small_scenario();
  scenario["soil"] = {{"type", "clm"}, {"params", soil_properties()}};
  const auto result_file = dir / "calibration.json";
  const t::CliResult r = t::run_rumble({"calibrate", t::write_scenario(dir, scenario).string(),
                                        "--model", "winkler", "--params", R"({"k": 1e8, "c": 1e5})",
                                        "--terms", "0", "--output", result_file.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json report = t::read_json(result_file);
  auto single = make_soil("winkler", soil_properties(), sleeper_row(1));
  const Lumped footing = lumped_parameters(*single, 1);
  EXPECT_NEAR(report.at("params").at("k").get<double>() / footing.k_f, 1.0, 1e-6);
  EXPECT_NEAR(report.at("params").at("c").get<double>() / footing.c_f, 1.0, 1e-6);
  EXPECT_LT(report.at("relative_rms_residual").get<double>(), 1e-6);
}

}  // namespace
}  // namespace rumble::soiltest
