// winkler from soil properties against the closed forms it implements and the numbers of
// docs/physics.md §6.1 / §10 case 7 (2.6 x 0.26 m footprint, nu = 0.3, rho = 1800 kg/m^3):
//   K_z = 2 G L / (1 - nu) (0.73 + 1.54 (B/L)^0.75)   Gazetas (1991), 2L x 2B = 2.6 x 0.26 m
//   C_z = rho V_La A, V_La = 3.4 c_s / (pi (1 - nu))   Lysmer's analog
//   m   = 2.4 (nu - 1/3) rho pi r0^3, r0 = sqrt(A/pi)  Wolf's cone trapped mass, 0 for nu <= 1/3
// The stiffness is read through initialize() (u = F / K), the dashpot and mass through
// frequency_response (1/H = K - w^2 m + i w C).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

constexpr double kLength = 2.6, kWidth = 0.26;  // m

struct TableRow {
  const char* name;
  double E;        // Pa
  double K_table;  // N/m, docs/physics.md §6.1 (3 significant digits)
  double C_table;  // N s/m, docs/physics.md §6.1
};
constexpr TableRow kTable[] = {{"soft", 10e6, 1.43e7, 8.70e4},
                               {"medium", 155e6, 2.22e8, 3.42e5},
                               {"stiff", 750e6, 1.08e9, 7.53e5}};

/// Half a unit of the third significant digit of x: the rounding of a 3-digit table value
/// (0.23 % to 0.46 % of it here).
double three_digit_rounding(double x) {
  return 0.005 * std::pow(10.0, std::floor(std::log10(std::abs(x))));
}

double gazetas(double E, double nu) {
  const double G = E / (2.0 * (1.0 + nu)), L = kLength / 2.0, B = kWidth / 2.0;
  return 2.0 * G * L / (1.0 - nu) * (0.73 + 1.54 * std::pow(B / L, 0.75));
}

double lysmer(double E, double nu, double rho) {
  const double cs = std::sqrt(E / (2.0 * (1.0 + nu)) / rho);
  return rho * 3.4 * cs / (std::numbers::pi * (1.0 - nu)) * kLength * kWidth;
}

TEST(SoilFootingStiffness, WinklerFromSoilIsGazetasThroughInitialize) {
  for (const TableRow& row : kTable) {
    const Index n = 5;
    auto soil = make_soil("winkler", soil_properties(row.E), sleeper_row(n));
    VectorXd F(n);
    for (Index i = 0; i < n; ++i) F[i] = 5e4 * static_cast<double>(i + 1);  // N, all different
    const VectorXd u = static_displacement(*soil, F);
    for (Index i = 0; i < n; ++i) {
      const double K = F[i] / u[i];
      // The plugin evaluates the same formula: only round-off may differ.
      EXPECT_NEAR(K, gazetas(row.E, 0.3), 1e-12 * K) << row.name << ", footprint " << i;
      EXPECT_NEAR(K, row.K_table, three_digit_rounding(row.K_table)) << row.name;
    }
    std::printf("  %-6s K = F/u = %.4e N/m (docs/physics.md %.3g)\n", row.name, F[0] / u[0],
                row.K_table);
  }
}

TEST(SoilFootingStiffness, WinklerDashpotIsLysmerAndNoMassBelowOneThird) {
  const double f = 50.0,
               w = 2.0 * std::numbers::pi * f;  // Hz, rad/s: any frequency does (constant C)
  for (const TableRow& row : kTable) {
    auto soil = make_soil("winkler", soil_properties(row.E), sleeper_row(3));
    const std::complex<double> D = 1.0 / receptance(*soil, f, 3)(1, 1);
    const double C = D.imag() / w;
    EXPECT_NEAR(C, lysmer(row.E, 0.3, 1800.0), 1e-12 * C) << row.name;
    EXPECT_NEAR(C, row.C_table, three_digit_rounding(row.C_table)) << row.name;
    // nu = 0.3 <= 1/3: no trapped mass, so Re(1/H) is the static stiffness at any frequency.
    EXPECT_NEAR(D.real(), gazetas(row.E, 0.3), 1e-12 * D.real()) << row.name;
    std::printf("  %-6s C = %.4e N s/m (docs/physics.md %.3g)\n", row.name, C, row.C_table);
  }
}

TEST(SoilFootingStiffness, WinklerTrappedMassAboveOneThird) {
  const double nu = 0.4, rho = 1800.0;
  auto soil = make_soil("winkler", soil_properties(155e6, nu, rho), sleeper_row(1));
  const Lumped p = lumped_parameters(*soil, 1);
  const double r0 = std::sqrt(kLength * kWidth / std::numbers::pi);
  const double wolf = 2.4 * (nu - 1.0 / 3.0) * rho * std::numbers::pi * r0 * r0 * r0;  // 90.3 kg
  // m comes from a difference of two stiffnesses ~1e8 N/m divided by w^2 = 3.9e3 1/s^2:
  // round-off ~1e-16 * 1e8 / 3.9e3 ~ 1e-11 kg.
  EXPECT_NEAR(p.m_f, wolf, 1e-6);
  EXPECT_NEAR(p.k_f, gazetas(155e6, nu), 1e-12 * p.k_f);
  EXPECT_NEAR(p.c_f, lysmer(155e6, nu, rho), 1e-12 * p.c_f);
}

TEST(SoilFootingStiffness, WinklerFootprintsDoNotInteract) {
  auto soil = make_soil("winkler", soil_properties(), sleeper_row(5));
  VectorXd F = VectorXd::Zero(5);
  F[2] = 1e5;  // N on the middle footprint only
  const VectorXd u = static_displacement(*soil, F);
  EXPECT_GT(u[2], 0.0);  // z down: a downward force pushes the footprint down
  for (const Index i : {0, 1, 3, 4}) EXPECT_EQ(u[i], 0.0) << "footprint " << i;
}

}  // namespace
}  // namespace rumble::soiltest
