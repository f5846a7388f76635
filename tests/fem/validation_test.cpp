// The FEM soil on meshes too large for the default suite (label `validation`, excluded from
// `ctest -LE validation`; run with `ctest --preset dev -L validation`): the footing settlement
// converging under refinement (docs/fem-soil.md section 6), a receiver's PPV on finer meshes than
// the default suite's (ppv_convergence_test.cpp), and the Rayleigh wave's speed between two
// surface receivers far from the load (docs/fem-soil.md section 6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "correlation_lag.hpp"
#include "lamb_surface.hpp"
#include "receiver_ppv.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

double footing_settlement(double h_near) {
  const nlohmann::json p = {
      {"E", 155e6},
      {"nu", 0.3},
      {"rho", 1800.0},
      {"mesh", {{"radius", 12.0}, {"h_near", h_near}, {"near_distance", 2.0}}}};
  TestSoil soil("fem", p.dump());
  soil.accept_layout({{0.0, 0.0, 1.0, 1.0}});
  return soil.initialize(VectorXd::Constant(1, 1e5))[0];
}

TEST(FemValidation, FootingSettlementConvergesFromBelow) {
  const double exact = 0.946 * 1e5 * (1.0 - 0.09) / 155e6;  // docs/soils.md (Love), B = 1 m
  const double coarse = footing_settlement(0.25), fine = footing_settlement(0.125);
  std::printf("settlement / closed form: %.4f at B/4, %.4f at B/8\n", coarse / exact, fine / exact);
  // Measured with the half-space's far field (docs/fem-soil.md section 3.2): -11.0 % and
  // -4.0 %, the error falling 2.7x for h / 2 (order 1.45: the pressure's jump at the footing's
  // edge). With Liu's springs it was -9.2 % and -2.2 % (4.2x), the boundary's softness
  // making up part of the elements' stiffness.
  EXPECT_LT(coarse, fine);
  EXPECT_LT(fine, exact);
  EXPECT_LT(std::abs(fine / exact - 1.0), 0.05);
  EXPECT_GT((exact - coarse) / (exact - fine), 2.4);
}

TEST(FemValidation, ReceiverPpvConvergesOnFinerMeshes) {
  // The default suite's case on four meshes, h = 0.6 / sqrt(2)^k m, k = 0..3 (8 to 23 elements
  // per Rayleigh wavelength at 75 Hz), and the order from a least-squares fit of
  // PPV(h) = PPV_inf + c h^p to all four (three successive meshes alone give an order between 0.7
  // and 3.1 here: on the finer ones the differences, 4e-7 m/s, are as small as the scatter of
  // the receivers' interpolation, the four receivers' spread). Measured: 9.991e-5, 1.0134e-4,
  // 1.0181e-4, 1.0217e-4 m/s; p = 2.5, PPV_inf 1.0231e-4 m/s, rms 4.8e-8.
  const double r = std::sqrt(2.0);
  std::vector<double> h, ppv;
  for (int k = 0; k < 4; ++k) {
    h.push_back(0.6 / std::pow(r, k));
    const RingPpv ring = ring_ppv(h.back(), 3.0, 8.0, 0.02, 0.03);
    ppv.push_back(ring.mean());
    std::printf("h %.4f m: PPV %.5e m/s (spread %.2e)\n", h.back(), ppv.back(), ring.spread());
  }
  const OrderFit fit = fit_order(h, ppv);
  RecordProperty("fitted_order", std::to_string(fit.order));
  std::printf("fit: order %.2f, PPV_inf %.5e m/s, rms %.2e\n", fit.order, fit.p_inf, fit.rms);
  for (int k = 1; k < 3; ++k)
    EXPECT_LT(std::abs(ppv[k + 1] - ppv[k]), std::abs(ppv[k] - ppv[k - 1])) << "k = " << k;
  EXPECT_GT(fit.order, 1.5);
  EXPECT_LT(fit.order, 4.0);
  EXPECT_LT(std::abs(ppv[3] - fit.p_inf), 0.01 * fit.p_inf);
}

TEST(FemValidation, RayleighPulseSpeedBetweenFarReceivers) {
  // Lamb's half-space (E 45 MPa, nu 0.25, rho 1800: c_s 100, c_R 91.94 m/s), a 0.3 x 0.3 m
  // footprint loaded by a triangle pulse (10 kN, rising over 40 ms and falling over 40 ms: its
  // spectrum mostly below 25 Hz, a Rayleigh wavelength of 3.7 m or more, 12 elements of
  // h_near 0.3 m), receivers on the surface at 4 and 8 m, a 12 m hemisphere. The speed is the
  // distance over the lag of the cross-correlation of the two u_z traces, up to 0.17 s (before
  // the Rayleigh wave's echo from the rim reaches 8 m). Measured: 87.67 m/s from the mesh,
  // 87.93 m/s from the closed form's own traces (0.3 %; bound 2 %, docs/physics.md §10 case 2); the
  // closed form's lag itself is 4.4 % below c_R: at 1-2 Rayleigh wavelengths the displacement
  // still carries the quasi-static (Boussinesq) part of the load, which does not travel at c_R
  // (a check of c_R itself needs receivers farther apart or the Rayleigh pulse alone).
  constexpr double E = 45e6, nu = 0.25, rho = 1800.0, P = 1e4, T = 0.04, H = 1e-3;
  const std::vector<double> r = {4.0, 8.0};
  const nlohmann::json params = {
      {"E", E},
      {"nu", nu},
      {"rho", rho},
      {"damping", {{"ratio", 0.0}}},
      {"mesh", {{"radius", 12.0}, {"h_near", 0.3}, {"near_distance", 8.5}}}};
  TestSoil soil("fem", params.dump());
  soil.accept_layout({{0.0, 0.0, 0.3, 0.3}});
  std::vector<rumble_probe> probes;
  for (double d : r) probes.push_back({"r", 0.0, d, 0.0});
  ASSERT_EQ(soil.api().set_probes(soil.self(), probes.data(), probes.size(), H), RUMBLE_OK);
  soil.initialize(VectorXd::Zero(1));
  const auto ramp = [](double t) { return t <= 0.0 ? 0.0 : P * std::min(t / T, 1.0); };
  const auto load = [&](double t) { return ramp(t) - ramp(t - T); };  // a triangle
  std::vector<std::vector<double>> fem(r.size()), exact(r.size());
  const auto closed_form = [&](double t, double d) {
    const auto u = [&](double s) {
      return s <= 0.0 ? 0.0 : lamb_ramped_surface_displacement(s, d, P, E, nu, rho, T);
    };
    return u(t) - u(t - T);
  };
  soil.drive_probes(load, H, 0.17, probes.size(), [&](double t, std::size_t p, const double* v) {
    fem[p].push_back(v[5]);
    exact[p].push_back(closed_form(t, r[p]));
  });
  const double c_fem = (r[1] - r[0]) / correlation_lag(fem[0], fem[1], H);
  const double c_exact = (r[1] - r[0]) / correlation_lag(exact[0], exact[1], H);
  const double c_R = 100.0 * rayleigh_speed_ratio(nu);
  RecordProperty("c_fem", std::to_string(c_fem));
  RecordProperty("c_closed_form", std::to_string(c_exact));
  std::printf("c_R %.2f m/s: the closed form's traces %.2f, the mesh %.2f m/s\n", c_R, c_exact,
              c_fem);
  EXPECT_NEAR(c_fem / c_exact, 1.0, 0.02);
  EXPECT_NEAR(c_exact / c_R, 0.956, 0.01);  // the method's own bias (above)
}

}  // namespace
}  // namespace rumble::test
