// The SDK example sdk/examples/prescribed_load, built out of tree and installed as users do
// (build_and_run_example.cmake), run by the installed rumble on its lamb.json: Lamb's problem on
// the FEM soil, 10 kN ramped over 6 ms on a 0.3 x 0.3 m footprint of an elastic half-space
// (E = 750 MPa, nu = 0.25), surface receivers 2 and 3 m away. Against the independent reference
// of the FEM soil's own Lamb test (tests/support/lamb_surface.hpp: Kausel's closed form of the
// ramped point load; docs/physics.md §4 and §10 case 1):
//   - nothing moves at a receiver before the P wave can reach it;
//   - the surface rises to half its final value when the closed form does (the arrival of the
//     Rayleigh wave, smoothed by the ramp);
//   - it settles to Boussinesq's static displacement (1 - nu) P / (2 pi G r), the closed form's
//     plateau;
//   - the whole record is within a relative L2 error of the closed form.
// The bounds are the FEM soil's Lamb test's, which measured this resolution (h_near 0.35 m, 6-7
// elements over the distance the Rayleigh front travels during the ramp; docs/fem-soil.md §6:
// arrivals and plateau within 2 %, L2 4-9 % at 2.5-4.5 m). The load is also what
// footprint_force.csv says the soil took: the static force plus the ramp, on that footprint
// only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"
#include "lamb_surface.hpp"

namespace rumble::testing {
namespace {

const std::filesystem::path kResults = LAMB_RESULTS;

/// The example's scenario: the soil, the load and the receivers the checks are made for.
struct Lamb {
  double E = 0.0, nu = 0.0, rho = 0.0;  // Pa, -, kg/m^3
  double P = 0.0, ramp = 0.0, x = 0.0;  // N, s, m: the loaded footprint's x
};

Lamb scenario() {
  std::ifstream in(LAMB_SCENARIO);
  const nlohmann::json s = nlohmann::json::parse(in);
  const nlohmann::json& soil = s.at("soil").at("params");
  const nlohmann::json& load = s.at("coupling").at("params");
  EXPECT_EQ(load.at("shape"), "ramp");
  return {soil.at("E"),    soil.at("nu"),        soil.at("rho"),
          load.at("load"), load.at("rise_time"), load.at("x")};
}

/// The column of `name` in a CSV file's header (0: time), or fails.
std::size_t column(const std::filesystem::path& file, const std::string& name) {
  std::istringstream text(file_text(file));
  std::string header, cell;
  std::getline(text, header);
  std::istringstream cells(header);
  for (std::size_t k = 0; std::getline(cells, cell, ','); ++k)
    if (cell == name) return k;
  ADD_FAILURE() << file << " has no column '" << name << "': " << header;
  return 0;
}

/// One receiver's vertical displacement [m] (down +) less its value at t = 0 (the static state
/// under the 1 kg wheel), and its times [s].
struct Trace {
  std::vector<double> t, uz;
};

Trace receiver(const std::string& name) {
  const std::filesystem::path file = kResults / "receivers.csv";
  std::vector<double> t, values;
  read_csv(file, t, values);
  const std::size_t width = t.empty() ? 1 : values.size() / t.size();
  const std::size_t c = column(file, name + " uz [m]") - 1;
  Trace tr;
  tr.t = t;
  for (std::size_t k = 0; k < t.size(); ++k) tr.uz.push_back(values[k * width + c] - values[c]);
  return tr;
}

/// First time [s] a trace reaches half of its final value (linear between samples).
double half_rise(const std::vector<double>& t, const std::vector<double>& u) {
  const double half = 0.5 * u.back();
  for (std::size_t k = 1; k < t.size(); ++k)
    if (u[k] >= half && u[k - 1] < half)
      return t[k - 1] + (t[k] - t[k - 1]) * (half - u[k - 1]) / (u[k] - u[k - 1]);
  return NAN;
}

TEST(PrescribedLoadLamb, TheSurfaceFollowsLambsClosedForm) {
  const Lamb lamb = scenario();
  const nlohmann::json summary = read_json(kResults / "summary.json");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_FALSE(summary["divergence"]["detected"].get<bool>());
  const double G = lamb.E / (2.0 * (1.0 + lamb.nu));
  const double c_p = std::sqrt(lamb.E * (1.0 - lamb.nu) /
                               (lamb.rho * (1.0 + lamb.nu) * (1.0 - 2.0 * lamb.nu)));  // m/s
  // Measured (dev build, 3.2e4 DOFs): at 2 m L2 0.037, half rise 0.989, plateau 1.012, before
  // the P wave 1.1e-4 of the peak; at 3 m 0.063, 0.982, 0.987, 3.3e-5. The bounds are the FEM
  // soil's Lamb test's (3 % on the arrival and the plateau, 1e-3 before P), L2 0.1. The load on
  // the footprint 1.5 m along the track (x = 0) reads plateaus 0.80 and 0.89, half rises 1.14
  // and 1.07; half the load, plateaus 0.51 and 0.49: both fail.
  const std::vector<std::pair<std::string, double>> receivers = {{"r2", 2.0}, {"r3", 3.0}};
  for (const auto& [name, r] : receivers) {
    SCOPED_TRACE(name);
    const Trace fem = receiver(name);
    ASSERT_GT(fem.t.size(), 50u);
    std::vector<double> exact;
    double peak = 0.0, error2 = 0.0, norm2 = 0.0, before_p = 0.0;
    for (std::size_t k = 0; k < fem.t.size(); ++k) {
      exact.push_back(rumble::test::lamb_ramped_surface_displacement(fem.t[k], r, lamb.P, lamb.E,
                                                                     lamb.nu, lamb.rho, lamb.ramp));
      peak = std::max(peak, std::abs(exact[k]));
      error2 += std::pow(fem.uz[k] - exact[k], 2);
      norm2 += exact[k] * exact[k];
      if (fem.t[k] < 0.8 * r / c_p) before_p = std::max(before_p, std::abs(fem.uz[k]));
    }
    const double boussinesq = (1.0 - lamb.nu) * lamb.P / (2.0 * std::acos(-1.0) * G * r);  // m
    EXPECT_NEAR(exact.back() / boussinesq, 1.0, 1e-6) << "the closed form has settled";
    std::printf("%s: L2 %.4f, half rise %.4f, plateau %.4f, before P %.2e of the peak\n",
                name.c_str(), std::sqrt(error2 / norm2),
                half_rise(fem.t, fem.uz) / half_rise(fem.t, exact), fem.uz.back() / boussinesq,
                before_p / peak);
    EXPECT_LT(before_p, 1e-3 * peak);
    EXPECT_NEAR(half_rise(fem.t, fem.uz) / half_rise(fem.t, exact), 1.0, 0.03);
    EXPECT_NEAR(fem.uz.back() / boussinesq, 1.0, 0.03);
    EXPECT_LT(std::sqrt(error2 / norm2), 0.1);
  }
}

TEST(PrescribedLoadLamb, TheSoilTookTheStaticForcesAndTheRampOnTheLoadedFootprint) {
  const Lamb lamb = scenario();
  const std::filesystem::path file = kResults / "footprint_force.csv";
  std::vector<double> t, f;
  read_csv(file, t, f);
  ASSERT_FALSE(t.empty());
  const std::size_t width = f.size() / t.size();
  ASSERT_EQ(width, 3u);
  const std::size_t loaded = column(file, "x=1.500 m [N]") - 1;
  for (std::size_t k = 0; k < t.size(); ++k) {
    for (std::size_t i = 0; i < width; ++i) {
      const double load = i == loaded ? lamb.P * std::min(t[k] / lamb.ramp, 1.0) : 0.0;
      EXPECT_NEAR(f[k * width + i], f[i] + load, 1e-6 * lamb.P) << "t = " << t[k] << ", " << i;
    }
  }
}

}  // namespace
}  // namespace rumble::testing
