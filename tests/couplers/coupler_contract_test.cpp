// The coupler contract (docs/couplers.md, "The coupler contract"; decision 0013), through a
// coupler that applies a load of its own: the SDK example sdk/examples/prescribed_load, built
// here against the build tree's SDK (tests/sdk_examples builds it out of tree, as users do).
// On the small Winkler scenario with a 1 kg wheel at rest (nothing static to speak of), 10 kN
// ramped over 5 ms from t = 2 ms on the footprint nearest x = 3.05 m:
//   - the host gives the layout (ABI 1.4): the footprint at x = 3.0 m takes the load;
//   - the static forces are get_output(track) at t0, and a soil keeps them until a coupler sets
//     its input: the coupler adds them, the other footprints keep them, nothing moves before
//     the load starts;
//   - footprint_force.csv and interface.csv hold what the soil took, not the track's forces;
//   - the divergence guard, with no static settlement to scale by, lets Lamb's problem run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

constexpr double kLoad = 1e4, kRise = 5e-3, kStart = 2e-3;  // N, s, s
constexpr std::size_t kLoaded = 5;                          // x = 3.0 m: sleepers 0.6 m apart
constexpr double kSpring = 1e8;                             // N/m per footprint (winkler k)

double ramp_load(double t) {
  return t <= kStart ? 0.0 : kLoad * std::min((t - kStart) / kRise, 1.0);
}

nlohmann::json prescribed_scenario() {
  nlohmann::json s = small_scenario();
  s["time"]["end"] = 0.03;
  s["vehicles"][0]["speed"] = 0.0;
  s["vehicles"][0]["params"] = {{"mass", 1.0}, {"static_load", 0.0}};
  s["soil"]["params"] = {{"k", kSpring}, {"c", 2e5}};
  s["plugins"] = {PRESCRIBED_LOAD_PLUGIN};
  s["coupling"] = {
      {"type", "prescribed_load"},
      {"params", {{"load", kLoad}, {"rise_time", kRise}, {"start", kStart}, {"x", 3.05}}}};
  return s;
}

struct Table {
  std::vector<double> t, values;  // values row after row
  std::size_t width = 0;
  double at(std::size_t row, std::size_t column) const { return values[row * width + column]; }
};

Table table(const std::filesystem::path& file) {
  Table x;
  read_csv(file, x.t, x.values);
  x.width = x.t.empty() ? 0 : x.values.size() / x.t.size();
  return x;
}

TEST(CouplerContract, AProbeLoadGoesWhereTheLayoutSaysAndIsRecordedAsTheSoilTookIt) {
  const auto dir = scratch_directory("coupler_contract_prescribed");
  const CliResult r =
      run_rumble({"run", write_scenario(dir, prescribed_scenario()).string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("no static load to scale the divergence bound by"));
  const auto results = dir / "results";
  const nlohmann::json summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_FALSE(summary["divergence"]["detected"].get<bool>());
  EXPECT_TRUE(summary["divergence"]["displacement_bound_m"].is_null());

  const Table force = table(results / "footprint_force.csv");
  const Table u = table(results / "footprint_displacement.csv");
  const Table v = table(results / "footprint_velocity.csv");
  const Table power = table(results / "interface.csv");
  ASSERT_EQ(force.t.size(), 31u);
  ASSERT_EQ(force.width, 20u);
  std::istringstream header(file_text(results / "footprint_force.csv"));
  std::string columns;
  std::getline(header, columns);
  EXPECT_THAT(columns, ::testing::StartsWith("t [s],x=0.000 m [N],x=0.600 m [N]"));
  EXPECT_THAT(columns, ::testing::HasSubstr(",x=2.400 m [N],x=3.000 m [N],x=3.600 m [N]"));
  double energy = 0.0;  // J, the work of the recorded forces on the recorded displacements
  for (std::size_t k = 0; k < force.t.size(); ++k) {
    SCOPED_TRACE("t = " + std::to_string(force.t[k]));
    double p = 0.0;  // W
    for (std::size_t i = 0; i < force.width; ++i) {
      // What the soil took: the static forces (row 0), plus the load on footprint 5 only.
      const double expected = force.at(0, i) + (i == kLoaded ? ramp_load(force.t[k]) : 0.0);
      EXPECT_NEAR(force.at(k, i), expected, 1e-6 * kLoad) << "footprint " << i;
      if (i != kLoaded) {
        EXPECT_NEAR(u.at(k, i), u.at(0, i), 1e-12) << "footprint " << i;
      }
      p += force.at(k, i) * v.at(k, i);
      if (k > 0) {
        energy += 0.5 * (force.at(k - 1, i) + force.at(k, i)) * (u.at(k, i) - u.at(k - 1, i));
      }
    }
    EXPECT_NEAR(power.at(k, 1), p, 1e-6 * std::abs(p) + 1e-9) << "power at the cut [W]";
    EXPECT_NEAR(power.at(k, 2), energy, 1e-6 * std::abs(energy) + 1e-9) << "energy [J]";
    if (force.t[k] <= kStart) {
      EXPECT_NEAR(u.at(k, kLoaded), u.at(0, kLoaded), 1e-15) << "no load yet";
    }
  }
  // The load reached the soil: its spring (k = 1e8 N/m, c / k = 2 ms) settles under it by P / k,
  // 23 ms after the ramp, to exp(-23 / 2) = 1e-5 of the transient.
  EXPECT_NEAR(u.at(30, kLoaded) - u.at(0, kLoaded), kLoad / kSpring, 1e-4 * kLoad / kSpring);
}

}  // namespace
}  // namespace rumble::testing
