// Lamb's problem through the plugin's C table: a vertical load ramped to P over t_ramp on a small
// square footprint of the FEM half-space, surface receivers at two distances, against the closed
// form (tests/support/lamb_surface.hpp, Kausel / Pekeris): the motion before the P wave, the
// Rayleigh pulse's time and depth, the static plateau, and the Rayleigh speed from the two
// receivers (docs/physics.md §10 cases 1 and 2).
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "correlation_lag.hpp"
#include "lamb_surface.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

constexpr double kE = 45e6, kNu = 0.25, kRho = 1800.0;  // G = 18 MPa: c_s = 100 m/s
constexpr double kP = 1e4, kRamp = 0.025, kH = 1e-3;    // N, s, s

struct Trace {
  std::vector<double> t, uz, vz;  // s, m, m/s (down +)
};

/// The load [N]: ramped to P over kRamp and held, or (pulse) a triangle of height P rising and
/// falling over kRamp each: ramp(t) - ramp(t - kRamp).
double load(double t, bool pulse) {
  const auto ramp = [](double s) { return s <= 0.0 ? 0.0 : kP * std::min(s / kRamp, 1.0); };
  return pulse ? ramp(t) - ramp(t - kRamp) : ramp(t);
}

double closed_form(double t, double r, bool pulse) {
  const auto ramp = [r](double s) {
    return s <= 0.0 ? 0.0 : lamb_ramped_surface_displacement(s, r, kP, kE, kNu, kRho, kRamp);
  };
  return pulse ? ramp(t) - ramp(t - kRamp) : ramp(t);
}

/// Surface receivers at y = distances [m] (x = 0), recorded over [0, t_end] [s].
std::vector<Trace> run_lamb(const std::vector<double>& distances, double t_end, bool pulse) {
  const nlohmann::json params = {
      {"E", kE},
      {"nu", kNu},
      {"rho", kRho},
      {"damping", {{"ratio", 0.0}}},  // elastic, as Lamb
      {"mesh", {{"radius", 10.0}, {"h_near", 0.35}, {"near_distance", 5.0}}}};
  TestSoil soil("fem", params.dump());
  soil.accept_layout({{0.0, 0.0, 0.3, 0.3}});
  std::vector<rumble_probe> probes;
  for (double d : distances) probes.push_back({"r", 0.0, d, 0.0});
  EXPECT_EQ(soil.api().set_probes(soil.self(), probes.data(), probes.size(), 0.0), RUMBLE_OK);
  soil.initialize(VectorXd::Zero(1));
  std::vector<Trace> traces(distances.size());
  soil.drive_probes([pulse](double t) { return load(t, pulse); }, kH, t_end, probes.size(),
                    [&](double t, std::size_t p, const double* v) {
                      traces[p].t.push_back(t);
                      traces[p].uz.push_back(v[5]);
                      traces[p].vz.push_back(v[2]);
                    });
  return traces;
}

/// First time [s] at which a trace reaches half of its final value (linear between samples).
double half_rise_time(const std::vector<double>& t, const std::vector<double>& u) {
  const double half = 0.5 * u.back();
  for (std::size_t k = 1; k < t.size(); ++k)
    if (u[k] >= half && u[k - 1] < half)
      return t[k - 1] + (t[k] - t[k - 1]) * (half - u[k - 1]) / (u[k] - u[k - 1]);
  return NAN;
}

TEST(FemLamb, SurfaceResponseToARampedPointLoad) {
  // Measured with this mesh (h_near 0.35 m, 6-7 elements over the 2.3 m the Rayleigh front
  // travels during the ramp): relative L2 error 0.042 at 2.5 m and 0.091 at 4.5 m (dispersion
  // of linear elements, which grows with the distance travelled), plateau within 1.5 %, half
  // rise within 1.6 %. The bounds leave about 1.5x margin; a regression in the operators (a
  // wrong Lame constant, mass, or load weight) moves them by far more.
  const std::vector<double> r = {2.5, 4.5};
  const std::vector<double> max_l2 = {0.07, 0.13};
  const std::vector<Trace> fem = run_lamb(r, 0.09, false);
  const double c_p = 100.0 * std::sqrt(3.0);
  for (std::size_t p = 0; p < r.size(); ++p) {
    SCOPED_TRACE("receiver at " + std::to_string(r[p]) + " m");
    const Trace& tr = fem[p];
    ASSERT_GT(tr.t.size(), 50u);
    std::vector<double> exact(tr.t.size());
    double peak = 0.0, error2 = 0.0, norm2 = 0.0, before_p = 0.0;
    for (std::size_t k = 0; k < tr.t.size(); ++k) {
      exact[k] = closed_form(tr.t[k], r[p], false);
      peak = std::max(peak, std::abs(exact[k]));
      error2 += std::pow(tr.uz[k] - exact[k], 2);
      norm2 += exact[k] * exact[k];
      if (tr.t[k] < 0.8 * r[p] / c_p) before_p = std::max(before_p, std::abs(tr.uz[k]));
    }
    EXPECT_LT(std::sqrt(error2 / norm2), max_l2[p]);
    EXPECT_LT(before_p, 1e-3 * peak);  // nothing before the P wave (measured 7e-5)
    EXPECT_NEAR(half_rise_time(tr.t, tr.uz) / half_rise_time(tr.t, exact), 1.0, 0.03);
    EXPECT_NEAR(tr.uz.back() / exact.back(), 1.0, 0.03);  // the Boussinesq plateau
  }
}

TEST(FemLamb, RayleighPulseTravelsAsTheClosedForm) {
  const std::vector<double> r = {2.0, 5.0};
  const std::vector<Trace> fem = run_lamb(r, 0.085, true);
  std::vector<double> exact0, exact1;
  for (double t : fem[0].t) {
    exact0.push_back(closed_form(t, r[0], true));
    exact1.push_back(closed_form(t, r[1], true));
  }
  const double c_fem =
      (r[1] - r[0]) / correlation_lag(fem[0].uz, fem[1].uz, fem[0].t[1] - fem[0].t[0]);
  const double c_exact = (r[1] - r[0]) / correlation_lag(exact0, exact1, fem[0].t[1] - fem[0].t[0]);
  // At 2-5 m the P and S near field still shapes the pulse, so the lag of the closed form's own
  // traces gives 98.1 m/s rather than c_R = 91.9 m/s: the mesh is compared with that (measured
  // 100.7 m/s, 2.7 %: linear tetrahedra at 6-7 elements per pulse length). c_R itself, from
  // receivers tens of wavelengths apart, needs a larger mesh: the validation suite.
  EXPECT_NEAR(c_exact / (100.0 * rayleigh_speed_ratio(kNu)), 1.07, 0.01);
  EXPECT_NEAR(c_fem / c_exact, 1.0, 0.04);
}

}  // namespace
}  // namespace rumble::test
