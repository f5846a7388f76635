// The half-space formulas behind the soil-derived parameters, from their headers: Boussinesq
// influence of flexible rectangles (docs/physics.md §6.2, §6.3), the centre stress, and the layered
// equivalent soil. Reference numbers: docs/physics.md (3 digits) and an independent Python script
// (40 x 40 and 80 x 80 Gauss points, scipy-free) for the 5-digit ones.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "boussinesq.hpp"
#include "boussinesq_field.hpp"
#include "layered_soil.hpp"

namespace rumble::soils {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(SoilHalfSpace, SquareMeanSettlementFactor) {
  // Mean settlement of a flexible square of side B: q B (1 - nu^2) / E * 0.946 (docs/physics.md
  // §6.2), i.e. an influence of 0.946 pi / B; Python: 0.946402.
  EXPECT_NEAR(mean_flexible_influence(1.0, 1.0, 0.0) / std::numbers::pi, 0.946402, 1e-5);
  EXPECT_NEAR(mean_flexible_influence(2.0, 2.0, 0.0) / std::numbers::pi, 0.946402 / 2, 1e-5);
}

TEST(SoilHalfSpace, NeighbourRatiosOfTheTable) {
  // docs/physics.md §6.3: 0.395, 0.412, 0.513 and u2/u0 = 0.249; Python (80 x 80): 0.394742,
  // 0.412464, 0.513439, 0.249256. 20 x 20 points are within 1e-5 of them.
  EXPECT_NEAR(neighbour_compliance_ratio(2.6, 0.26, 0.6), 0.394742, 1e-5);
  EXPECT_NEAR(neighbour_compliance_ratio(2.6, 0.30, 0.6), 0.412464, 1e-5);
  EXPECT_NEAR(neighbour_compliance_ratio(3.0, 0.50, 0.6), 0.513439, 1e-5);
  EXPECT_NEAR(neighbour_compliance_ratio(2.6, 0.26, 1.2), 0.249256, 1e-5);
}

TEST(SoilHalfSpace, CentreStressLimits) {
  EXPECT_NEAR(centre_vertical_stress(2.6, 0.26, 1e-9), 1.0, 1e-8);  // q at the surface
  // Far below, the load acts as a point force P = q A: 3 P / (2 pi z^2) (Boussinesq); the
  // relative difference is O((L / z)^2) ~ 2e-4 at z = 100 m.
  const double z = 100.0, point = 3 * 2.6 * 0.26 / (2 * std::numbers::pi * z * z);
  EXPECT_NEAR(centre_vertical_stress(2.6, 0.26, z), point, 1e-3 * point);
}

TEST(SoilHalfSpace, StressWeightsAddUp) {
  const double total = stress_weight(2.6, 0.26, 0.0, kInf);
  EXPECT_NEAR(total, 0.661516, 1e-6);  // Python, 20 to 640 points per panel agree
  EXPECT_NEAR(stress_weight(2.6, 0.26, 0.0, 1.0) + stress_weight(2.6, 0.26, 1.0, 3.0) +
                  stress_weight(2.6, 0.26, 3.0, kInf),
              total, 1e-12);
  EXPECT_NEAR(stress_weight(2.6, 0.26, 0.0, 1.0), 0.418212, 1e-6);
}

TEST(SoilHalfSpace, LayeredSoilEquivalent) {
  const SoilProperties stiff{750e6, 0.3, 1800}, soft{10e6, 0.35, 1600};
  // No layers, or layers of the half-space itself: the half-space.
  EXPECT_EQ(equivalent_properties({}, stiff, 2.6, 0.26).E, stiff.E);
  const SoilProperties same = equivalent_properties({{1.0, stiff}, {2.0, stiff}}, stiff, 2.6, 0.26);
  EXPECT_NEAR(same.E, stiff.E, 1e-12 * stiff.E);
  EXPECT_NEAR(same.nu, stiff.nu, 1e-12);
  // A layer 1000 times the footprint's size: the layer (its share of the stress integral is
  // 1 - O(A / depth) ~ 1 - 1e-4).
  const SoilProperties deep = equivalent_properties({{2600.0, soft}}, stiff, 2.6, 0.26);
  EXPECT_NEAR(deep.E, soft.E, 1e-3 * soft.E);
  // 1 m of soft soil over the stiff one: its weight is 0.418212 / 0.661516 = 0.632205, so
  // 1 / E_eq = 0.632205 / 10 MPa + 0.367795 / 750 MPa: E_eq = 15.69 MPa, the soft layer rules.
  const SoilProperties two = equivalent_properties({{1.0, soft}}, stiff, 2.6, 0.26);
  const double w = 0.418212 / 0.661516;
  EXPECT_NEAR(two.E, 1.0 / (w / soft.E + (1 - w) / stiff.E), 1e-5 * two.E);
  EXPECT_NEAR(two.nu, w * soft.nu + (1 - w) * stiff.nu, 1e-6);
  EXPECT_NEAR(two.rho, w * soft.rho + (1 - w) * stiff.rho, 1e-3);
}

}  // namespace
}  // namespace rumble::soils

namespace rumble::soils {
namespace {

/// The stress of Hooke's law from the displacement gradient by central differences of
/// boussinesq_point_load's displacement (step 1e-6 of the distance).
Eigen::Matrix3d stress_from_displacement(const Eigen::Vector3d& x, double G, double nu) {
  const double h = 1e-6 * x.norm();
  Eigen::Matrix3d gradient;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(j);
    gradient.col(j) = (boussinesq_point_load(x + step, 1.0, G, nu).displacement -
                       boussinesq_point_load(x - step, 1.0, G, nu).displacement) /
                      (2.0 * h);
  }
  const Eigen::Matrix3d strain = 0.5 * (gradient + gradient.transpose());
  const double lambda = 2.0 * G * nu / (1.0 - 2.0 * nu);
  return lambda * strain.trace() * Eigen::Matrix3d::Identity() + 2.0 * G * strain;
}

TEST(SoilHalfSpace, BoussinesqsStressIsHookesLawOfItsDisplacement) {
  // The closed-form stress against the displacement's strain (two formulas of the same field,
  // written separately), off and on the axis, at the surface and deep; G = 60 MPa, nu = 0.3.
  const double G = 60e6, nu = 0.3;
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.0, 0.5, 0.7), Eigen::Vector3d(-3.0, 2.0, 0.1),
                                   Eigen::Vector3d(0.2, -0.1, 4.0), Eigen::Vector3d(0.0, 0.0, 2.0),
                                   Eigen::Vector3d(12.0, -3.0, 0.0)}) {
    const Eigen::Matrix3d closed = boussinesq_point_load(x, 1.0, G, nu).stress;
    EXPECT_LT((closed - stress_from_displacement(x, G, nu)).norm(), 1e-6 * closed.norm())
        << x.transpose();
  }
}

TEST(SoilHalfSpace, BoussinesqsFieldFreesTheSurfaceAndCarriesTheLoad) {
  const double G = 60e6, nu = 0.35, P = 1e5;
  // The surface away from the load carries no traction: sigma e_z = 0 at z = 0.
  const Eigen::Matrix3d s = boussinesq_point_load({2.0, 1.0, 0.0}, P, G, nu).stress;
  EXPECT_LT(s.col(2).norm(), 1e-12 * s.norm());
  // The vertical stress over a horizontal plane at depth 1 m carries the load: the integral of
  // -sigma_zz over the plane (polar coordinates, 400 rings to 200 m, the tail 3/2 z^3 / r^4
  // beyond) is P; measured to 7e-8.
  double carried = 0.0;
  const double z = 1.0, r_max = 200.0;
  const int rings = 400;
  for (int k = 0; k < rings; ++k) {
    // rings spaced as r = z t^2 so that the axis region, where the stress peaks, is fine
    const double t0 = std::sqrt(r_max / z) * k / rings, t1 = std::sqrt(r_max / z) * (k + 1) / rings;
    const double r = z * 0.25 * (t0 + t1) * (t0 + t1), dr = z * (t1 * t1 - t0 * t0);
    carried -=
        boussinesq_point_load({r, 0.0, z}, P, G, nu).stress(2, 2) * 2.0 * std::numbers::pi * r * dr;
  }
  carried += P * 1.5 * z * z * z / (3.0 * r_max * r_max * r_max) * 2.0;  // (tail, tiny)
  EXPECT_NEAR(carried / P, 1.0, 1e-6);
  // u_z on the surface: (1 - nu) P / (2 pi G r), the settlement the FEM test compares against.
  const double r = 5.0;
  EXPECT_NEAR(boussinesq_point_load({0.0, r, 0.0}, P, G, nu).displacement[2],
              (1.0 - nu) * P / (2.0 * std::numbers::pi * G * r), 1e-12);
}

}  // namespace
}  // namespace rumble::soils
