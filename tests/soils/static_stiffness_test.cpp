// Parameters derived from soil properties, read back through the C API (statics and receptance)
// and compared with docs/physics.md §6.1 (footing impedances), §6.3 (chain ratio r) and §10
// cases 7-8. Those numbers have 3 significant digits: half a unit of the last digit is <= 0.4 %,
// hence the 0.5 % tolerances against them; closed forms re-typed here are met to 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <numbers>

#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

constexpr double kTable = 5e-3;  // relative, 3-digit table values

/// Gazetas (1991), rigid 2L x 2B, typed again from docs/soils.md §3.
double gazetas(const Soil& s, double length, double width) {
  const double G = s.E / (2 * (1 + s.nu)), L = length / 2, B = width / 2;
  return 2 * G * L / (1 - s.nu) * (0.73 + 1.54 * std::pow(B / L, 0.75));
}

/// Lysmer's analog dashpot, typed again from docs/soils.md §3.
double lysmer(const Soil& s, double area) {
  const double cs = std::sqrt(s.E / (2 * (1 + s.nu)) / s.rho);
  return s.rho * 3.4 * cs / (std::numbers::pi * (1 - s.nu)) * area;
}

/// Single-footprint winkler from soil: stiffness from statics, dashpot and mass from 1/H(f).
struct Footing {
  double k, c, m;
};
Footing winkler_footing(const nlohmann::json& params, double length, double width) {
  TestSoil soil("winkler", params.dump());
  soil.accept_layout(sleeper_row(1, 0.6, length, width));
  const double force = 1e5;  // N
  const double k = force / soil.initialize(VectorXd::Constant(1, force))[0];
  const double f = 50.0, w = 2 * std::numbers::pi * f;  // 1/H = k - w^2 m + i w c
  const std::complex<double> z = 1.0 / soil.receptance(f)(0, 0);
  return {k, z.imag() / w, (k - z.real()) / (w * w)};
}

TEST(SoilStatics, WinklerFromSoilMatchesGazetasAndLysmer) {
  // docs/physics.md §6.1 table: (soil, footprint) -> K_z [N/m], C_z [N s/m].
  struct Row {
    const Soil& soil;
    double length, width, K, C;
  };
  const Row rows[] = {
      {kSoils[0], 2.6, 0.26, 1.43e7, 8.70e4}, {kSoils[0], 3.0, 0.6, 1.96e7, 2.32e5},
      {kSoils[1], 2.6, 0.26, 2.22e8, 3.42e5}, {kSoils[1], 3.0, 0.6, 3.04e8, 9.12e5},
      {kSoils[2], 2.6, 0.26, 1.08e9, 7.53e5}, {kSoils[2], 3.0, 0.6, 1.47e9, 2.01e6}};
  for (const Row& r : rows) {
    SCOPED_TRACE(std::string(r.soil.name) + " " + std::to_string(r.length) + " x " +
                 std::to_string(r.width));
    const Footing f = winkler_footing(soil_params(r.soil), r.length, r.width);
    EXPECT_NEAR(f.k, r.K, kTable * r.K);
    EXPECT_NEAR(f.c, r.C, kTable * r.C);
    EXPECT_NEAR(f.k, gazetas(r.soil, r.length, r.width), 1e-12 * f.k);
    EXPECT_NEAR(f.c, lysmer(r.soil, r.length * r.width), 1e-9 * f.c);
    EXPECT_NEAR(f.m, 0.0, 1e-9);  // nu = 0.3 <= 1/3: no trapped mass (kg)
  }
}

TEST(SoilStatics, WinklerTrappedMassIsWolfsCone) {
  const Soil s{"nu 0.4", 155e6, 0.4, 1800.0};
  const Footing f = winkler_footing(soil_params(s), 2.6, 0.26);
  const double r0 = std::sqrt(2.6 * 0.26 / std::numbers::pi);
  const double wolf =
      2.4 * (0.4 - 1.0 / 3.0) * 1800.0 * std::numbers::pi * r0 * r0 * r0;  // 90.0 kg
  // m comes from Re(1/H) = k - w^2 m: k ~ 2.6e8, w^2 m ~ 8.9e6, round-off ~1e-16 k.
  EXPECT_NEAR(f.m, wolf, 1e-9 * wolf);
  // A given m replaces it.
  nlohmann::json p = soil_params(s);
  p["m"] = 0.0;
  EXPECT_NEAR(winkler_footing(p, 2.6, 0.26).m, 0.0, 1e-6);
}

TEST(SoilStatics, WinklerFootprintsDoNotInteract) {
  TestSoil soil("winkler", soil_params(kSoils[1]).dump());
  soil.accept_layout(sleeper_row(5));
  VectorXd F = VectorXd::Zero(5);
  F[2] = 1e5;
  const VectorXd u = soil.initialize(F);
  EXPECT_GT(u[2], 0.0);  // down under a downward force
  EXPECT_EQ(u[1], 0.0);
  EXPECT_EQ(u[3], 0.0);
}

/// Static displacements of a 41-footprint CLM row loaded at its middle footprint.
VectorXd clm_static_row(const nlohmann::json& params, double length = 2.6, double width = 0.26) {
  TestSoil soil("clm", params.dump());
  soil.accept_layout(sleeper_row(41, 0.6, length, width));
  VectorXd F = VectorXd::Zero(41);
  F[20] = 1e5;  // N
  return soil.initialize(F);
}

TEST(SoilStatics, CalibratedClmReproducesNeighbourRatioAndFootingStiffness) {
  for (const Soil& s : kSoils) {
    SCOPED_TRACE(s.name);
    const VectorXd u = clm_static_row(soil_params(s));
    // docs/physics.md §6.3 / §10 case 8: r = 0.395 (independent Python: 0.39474). The row's ends
    // are 20 spacings away: their effect is r^20 ~ 1e-8.
    EXPECT_NEAR(u[21] / u[20], 0.395, kTable * 0.395);
    EXPECT_NEAR(u[19] / u[20], u[21] / u[20], 1e-12);
    // The loaded footprint alone is as stiff as a single rigid footing (G0 = 1 / K_z).
    EXPECT_NEAR(1e5 / u[20], gazetas(s, 2.6, 0.26), 1e-6 * gazetas(s, 2.6, 0.26));
    // A chain's second neighbour is at r^2 = 0.156 (the half-space gives 0.249: the chain's
    // known limit, docs/soils.md).
    EXPECT_NEAR(u[22] / u[20], std::pow(u[21] / u[20], 2), 1e-7);
  }
}

TEST(SoilStatics, NeighbourRatioDependsOnGeometryAsTabulated) {
  // docs/physics.md §6.3 rows 2 and 3.
  const nlohmann::json medium = soil_params(kSoils[1]);
  const VectorXd a = clm_static_row(medium, 2.6, 0.30);
  EXPECT_NEAR(a[21] / a[20], 0.412, kTable * 0.412);
  const VectorXd b = clm_static_row(medium, 3.0, 0.50);
  EXPECT_NEAR(b[21] / b[20], 0.513, kTable * 0.513);
}

TEST(SoilStatics, MasslessClmDrivingPointIsTheSingleFooting) {
  // C = (C_z / K_z) K: the loaded footprint of the row responds as one footing,
  // H = 1 / (K_z + i w C_z), at every frequency (ends: r^20).
  const Soil& s = kSoils[1];
  TestSoil soil("clm", soil_params(s).dump());
  soil.accept_layout(sleeper_row(41));
  for (const double f : {0.0, 10.0, 40.0, 100.0}) {
    const std::complex<double> expected =
        1.0 / std::complex<double>(gazetas(s, 2.6, 0.26),
                                   2 * std::numbers::pi * f * lysmer(s, 2.6 * 0.26));
    EXPECT_LT(std::abs(soil.receptance(f)(20, 20) - expected), 1e-6 * std::abs(expected)) << f;
  }
}

}  // namespace
}  // namespace rumble::test
