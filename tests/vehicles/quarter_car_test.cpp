// quarter_car: equations, rigid-rail statics and modes against closed forms, tangent, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "rigid_rail.hpp"
#include "vehicle_harness.hpp"

namespace rumble::test {
namespace {

constexpr double kDefaultGravity = 9.81;  // m/s^2, the plugin's default

// Two masses: wheel 900 kg, bogie 700 kg, primary 1.5 MN/m, 6 kN s/m, payload 20 kN.
const char* const kTwoMassParams =
    R"({"wheel_mass": 900, "bogie_mass": 700, "primary": {"k": 1.5e6, "c": 6e3},
        "static_load": 2e4})";
// Three masses: as above plus a 4 t car body on 250 kN/m, 12 kN s/m.
const char* const kThreeMassParams =
    R"({"wheel_mass": 900, "bogie_mass": 700, "primary": {"k": 1.5e6, "c": 6e3},
        "secondary": {"car_body_mass": 4000, "k": 2.5e5, "c": 1.2e4}, "static_load": 2e4})";

TEST(QuarterCar, EquationsOfTheThreeMassChain) {
  TestVehicle v("quarter_car", kThreeMassParams);
  ASSERT_EQ(v.dofs(), 3);
  ASSERT_EQ(v.wheel_count(), 1);
  EXPECT_EQ(v.wheels()[0].offset, 0.0);
  EXPECT_EQ(v.wheels()[0].radius, 0.46);  // default
  const VectorXd q = (VectorXd(3) << 1e-3, 3e-3, 7e-3).finished();
  const VectorXd qd = (VectorXd(3) << 0.1, -0.2, 0.3).finished();
  const MatrixXd m = v.mass(q);
  EXPECT_EQ(m, (VectorXd(3) << 900, 700, 4000).finished().asDiagonal().toDenseMatrix());
  // Hand-written f; compression of each stage pushes its lower mass down, its upper mass up.
  const double primary = 1.5e6 * (3e-3 - 1e-3) + 6e3 * (-0.2 - 0.1);
  const double secondary = 2.5e5 * (7e-3 - 3e-3) + 1.2e4 * (0.3 + 0.2);
  const VectorXd expected =
      (VectorXd(3) << 900 * kDefaultGravity + primary, 700 * kDefaultGravity - primary + secondary,
       4000 * kDefaultGravity - secondary + 2e4)
          .finished();
  // Tolerance: a few ulps of the largest term (~4e4 N).
  EXPECT_LT((v.forces(q, qd) - expected).norm(), 1e-9);
  VectorXd z;
  MatrixXd j;
  v.wheel_kinematics(q, z, j);
  EXPECT_EQ(z(0), 1e-3);
  EXPECT_EQ(j, (MatrixXd(1, 3) << 1, 0, 0).finished());
  EXPECT_EQ(v.output_names(),
            (std::vector<std::string>{"primary_force [N]", "secondary_force [N]"}));
  EXPECT_NEAR(v.outputs(q, qd)(1), secondary, 1e-9);
}

TEST(QuarterCar, StaticWheelLoadIsTheWholeWeightPlusTheLoad) {
  TestVehicle v("quarter_car", kThreeMassParams);
  const Equilibrium e = rigid_rail_statics(v);
  const double expected = (900 + 700 + 4000) * kDefaultGravity + 2e4;  // N
  // An equilibrium, not an approximation: the Newton residual is < 1e-12 of the weight.
  EXPECT_NEAR(e.contact_force(0), expected, 1e-9 * expected);
  // Static deflections of the two stages: carried weight / stiffness.
  EXPECT_NEAR(e.q(1) - e.q(0), (700 + 4000) * kDefaultGravity / 1.5e6 + 2e4 / 1.5e6, 1e-12);
  EXPECT_NEAR(e.q(2) - e.q(1), 4000 * kDefaultGravity / 2.5e5 + 2e4 / 2.5e5, 1e-12);
}

TEST(QuarterCar, TwoMassRigidRailFrequencyIsBogieOnPrimary) {
  TestVehicle v("quarter_car", kTwoMassParams);
  const VectorXd f = rigid_rail_frequencies_hz(v, VectorXd::Zero(2));
  ASSERT_EQ(f.size(), 1);
  // Wheel held: one DOF, f = sqrt(k1 / m_b) / 2 pi. Eigen-solver accuracy ~1e-15 relative.
  EXPECT_NEAR(f(0), std::sqrt(1.5e6 / 700) / (2 * std::numbers::pi), 1e-10 * f(0));
}

TEST(QuarterCar, ThreeMassRigidRailFrequenciesMatchTheTwoDofClosedForm) {
  TestVehicle v("quarter_car", kThreeMassParams);
  const VectorXd f = rigid_rail_frequencies_hz(v, VectorXd::Zero(3));
  ASSERT_EQ(f.size(), 2);
  // Bogie m1 on k1 (to the held wheel), car body m2 on k2: the roots w^2 of
  //   m1 m2 w^4 - (m1 k2 + m2 (k1 + k2)) w^2 + k1 k2 = 0.
  const double m1 = 700, m2 = 4000, k1 = 1.5e6, k2 = 2.5e5;
  const double b = m1 * k2 + m2 * (k1 + k2);
  const double disc = std::sqrt(b * b - 4 * m1 * m2 * k1 * k2);
  const double low = std::sqrt((b - disc) / (2 * m1 * m2)) / (2 * std::numbers::pi);
  const double high = std::sqrt((b + disc) / (2 * m1 * m2)) / (2 * std::numbers::pi);
  EXPECT_NEAR(f(0), low, 1e-10 * low);  // about 1.2 Hz: car-body bounce
  EXPECT_NEAR(f(1), high, 1e-10 * high);
}

TEST(QuarterCar, TangentMatchesCentralDifferences) {
  TestVehicle v("quarter_car", kThreeMassParams);
  const VectorXd q = (VectorXd(3) << 1e-3, -2e-3, 4e-3).finished();
  const VectorXd qd = (VectorXd(3) << 0.2, 0.1, -0.3).finished();
  MatrixXd k, c, k_fd, c_fd;
  v.tangent(q, qd, k, c);
  // f is linear: central differences are exact but for round-off, |f| ~ 5e4 N * 1e-16 / 1e-6 m.
  central_difference_tangent(v, q, qd, 1e-6, 1e-6, k_fd, c_fd);
  EXPECT_LT((k - k_fd).cwiseAbs().maxCoeff(), 1e-6 * k.cwiseAbs().maxCoeff());
  EXPECT_LT((c - c_fd).cwiseAbs().maxCoeff(), 1e-6 * c.cwiseAbs().maxCoeff());
}

TEST(QuarterCar, DefaultsAreTheManchesterBenchmarkPerWheel) {
  TestVehicle v("quarter_car", "{}");
  ASSERT_EQ(v.dofs(), 2);
  EXPECT_EQ(v.mass(VectorXd::Zero(2)).diagonal(), (VectorXd(2) << 906.5, 653.75).finished());
}

TEST(QuarterCar, BadInputMessages) {
  EXPECT_EQ(creation_error("quarter_car", R"({"wheel_mass": -5})"),
            "params/wheel_mass: must be > 0 kg, got -5; give a positive mass in kg (per wheel)");
  EXPECT_EQ(creation_error("quarter_car", R"({"secondary": {"car_body_mass": 0}})"),
            "params/secondary/car_body_mass: must be > 0 kg, got 0; give a positive mass in kg "
            "(per wheel)");
  EXPECT_EQ(creation_error("quarter_car", R"({"primary": {"k": 1e6, "c": -1}})"),
            "params/primary/c: must be >= 0 N s/m, got -1; give the damping in N s/m (0 for none)");
  EXPECT_EQ(creation_error("quarter_car", R"({"bogie_mas": 700})"),
            "params/bogie_mas: unknown key (did you mean \"bogie_mass\"?); allowed keys here: "
            "bogie_mass, gravity, primary, secondary, static_load, wheel_mass, wheel_radius");
}

}  // namespace
}  // namespace rumble::test
