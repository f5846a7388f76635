// Receivers of an ABI 1.1 soil: named points (with depth) whose 3 velocity and 3 displacement
// components the soil samples inside its steps; the engine writes every sample to receivers.csv
// and the peaks to summary.json. picky_soil samples the nearest footprint's v and u as vz and uz
// at each of its sub-steps (8 per 1 ms step), so the samples can be checked against the
// footprint motion the engine records at macro-step ends.
#include <gtest/gtest.h>

#include <cmath>

#include "boundary_support.hpp"
#include "core/interrupt.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"

namespace rumble::testing {
namespace {

constexpr std::size_t kSubSteps = 8;    // 1 ms / picky_soil's 0.125 ms sub-step
constexpr std::size_t kFootprint = 10;  // x = 6.0 m: the receiver "under" sits there
constexpr std::size_t kColumns = 1 + 2 * RUMBLE_PROBE_VALUES;

TEST(Probes, SampledInsideStepsAndWrittenWithTheirPeaks) {
  // A force linear over the step, so that footprint_velocity.csv holds the soil's own velocity
  // at the step's end (under a held force it holds the step's mean: docs/couplers.md).
  nlohmann::json s = fixture_scenario(
      {{"type", "picky_soil"}}, {{"type", "gauss_seidel"}, {"params", {{"interpolation", 1}}}});
  s["outputs"]["receivers"] = {{{"name", "under"}, {"y", 0.0}, {"x", 6.0}, {"depth", 0.5}}, 2.5};
  CliResult r;
  const auto dir = run_in("probes_sampled", s, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  std::vector<double> times, values;
  read_csv(dir / "receivers.csv", times, values);
  const std::size_t steps = 50;
  ASSERT_EQ(times.size(), steps * kSubSteps);
  ASSERT_EQ(values.size(), times.size() * (kColumns - 1));
  for (std::size_t k = 0; k < times.size(); ++k)
    EXPECT_NEAR(times[k], (k + 1) * 1.25e-4, 1e-12) << k;

  // At every macro-step end the sample equals the recorded footprint motion (same doubles,
  // printed the same way).
  std::vector<double> t_v, fp_v, t_u, fp_u;
  read_csv(dir / "footprint_velocity.csv", t_v, fp_v);
  read_csv(dir / "footprint_displacement.csv", t_u, fp_u);
  const std::size_t n_fp = fp_v.size() / t_v.size();
  double peak_vz = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double* row = values.data() + k * (kColumns - 1);
    peak_vz = std::max(peak_vz, std::abs(row[2]));
    EXPECT_EQ(row[0], 0.0);  // vx: this soil has vertical motion only
    if ((k + 1) % kSubSteps != 0) continue;
    const std::size_t step = (k + 1) / kSubSteps;  // row of the footprint CSVs (0: t = 0)
    EXPECT_EQ(row[2], fp_v[step * n_fp + kFootprint]) << "vz at t = " << times[k];
    EXPECT_EQ(row[5], fp_u[step * n_fp + kFootprint]) << "uz at t = " << times[k];
  }
  const auto summary = read_json(dir / "summary.json");
  ASSERT_EQ(summary["ppv"].size(), 2u);
  EXPECT_EQ(summary["ppv"][0]["name"], "under");
  EXPECT_EQ(summary["ppv"][0]["depth_m"], 0.5);
  EXPECT_EQ(summary["ppv"][1]["name"], "d=2.5 m");
  // summary.json has the full double, receivers.csv 9 significant digits.
  EXPECT_NEAR(summary["ppv"][0]["ppv_m_s"].get<double>(), peak_vz, 1e-8 * peak_vz);
  EXPECT_GT(peak_vz, 0.0);
  // A soil that does not say which band it resolves (ABI 1.3 probe_resolution) leaves it null.
  EXPECT_TRUE(summary["ppv"][0]["resolved_f_hz"].is_null());
  EXPECT_FALSE(summary.contains("resolved_band_rule"));
}

// One that says it has it in the summary and the log; a negative frequency is its defect,
// named with the plugin, and the run stops (exit 3).
TEST(Probes, TheBandASoilResolvesIsRecordedAndANegativeOneIsItsDefect) {
  nlohmann::json s = fixture_scenario({{"type", "picky_soil"}, {"params", {{"resolution", 30.0}}}},
                                      {{"type", "gauss_seidel"}});
  s["outputs"]["receivers"] = {2.5, 5.0};
  CliResult r;
  const auto dir = run_in("probes_resolution", s, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("receivers resolved to: d=2.5 m 30 Hz, d=5 m 30 Hz (picky_soil's "
                          "params.resolution)"),
            std::string::npos)
      << r.output;
  const auto summary = read_json(dir / "summary.json");
  EXPECT_EQ(summary["ppv"][1]["resolved_f_hz"], 30.0);
  EXPECT_EQ(summary["resolved_band_rule"], "picky_soil's params.resolution");

  s["soil"]["params"]["resolution"] = -1.0;
  CliResult bad;
  run_in("probes_resolution_negative", s, bad);
  EXPECT_EQ(bad.exit_code, 3) << bad.output;
  EXPECT_NE(bad.output.find("probe_resolution returned -1.000000 Hz for probe 0, below 0 (0 says "
                            "the soil cannot tell): a defect of the plugin"),
            std::string::npos)
      << bad.output;
}

TEST(Probes, ARestoreDropsTheSamplesOfTheStepTakenAgain) {
  PluginRegistry registry;
  registry.load_library(fixture_plugin("boundary_fixtures"));
  const ComponentType* type = registry.find(RUMBLE_KIND_SOIL, "picky_soil");
  ASSERT_NE(type, nullptr);
  SoilInstance soil(*type, "/soil",
                    {{"k", 1e8},
                     {"c", 2e5},
                     {"sub_step", 1.25e-4},
                     {"max_step", 1.0},
                     {"stall_at", 1e30},
                     {"csc_defect", "none"}},
                    ".");
  soil.accept_layout({{0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}});
  std::vector<double> u;
  soil.initialize(0.0, {1e4, 2e4}, u);
  ASSERT_TRUE(soil.set_probes({{"p", 0.6, 0.0, 0.0}}, 0.0));
  std::vector<double> coeff{3e4, 3e4}, times, values;
  soil.checkpoint_save(0);
  const rumble_waveform force{0, 2, coeff.data()};
  soil.advance(0.0, 1e-3, force);
  soil.checkpoint_restore(0);
  soil.take_probe_samples(times, values);
  EXPECT_TRUE(times.empty()) << times.size() << " samples of an undone step survived";
  soil.advance(0.0, 1e-3, force);
  soil.take_probe_samples(times, values);
  EXPECT_EQ(times.size(), kSubSteps);
  EXPECT_EQ(values.size(), kSubSteps * RUMBLE_PROBE_VALUES);
}

}  // namespace
}  // namespace rumble::testing
