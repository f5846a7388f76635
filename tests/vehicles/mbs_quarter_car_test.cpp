// mbs reproduces quarter_car: the same chains of masses built from a JSON definition give the
// same M, f, tangent and rigid-rail frequencies as the hand-written plugin.
#include <gtest/gtest.h>

#include <string>

#include "rigid_rail.hpp"
#include "vehicle_harness.hpp"

namespace rumble::test {
namespace {

struct Pair {
  const char* quarter_car;
  const char* mbs;
};

// Same values as quarter_car_test. The mbs bodies sit at different nominal heights (frame
// origins) to show that only displacements matter; the elements have no preload, like
// quarter_car's springs, and b is the lower body of each.
const Pair kTwoMass{
    R"({"wheel_mass": 900, "bogie_mass": 700, "primary": {"k": 1.5e6, "c": 6e3},
        "static_load": 2e4})",
    R"({"bodies": [
          {"name": "wheel", "mass": 900, "transforms": [{"type": "tz", "value": -0.46, "dof": "z_w"}]},
          {"name": "bogie", "mass": 700, "transforms": [{"type": "tz", "value": -0.8, "dof": "z_b"}]}],
        "elements": [{"name": "primary", "body_a": "bogie", "body_b": "wheel", "k": 1.5e6, "c": 6e3}],
        "wheels": [{"body": "wheel"}],
        "loads": [{"body": "bogie", "force": 2e4}]})"};

const Pair kThreeMass{
    R"({"wheel_mass": 900, "bogie_mass": 700, "primary": {"k": 1.5e6, "c": 6e3},
        "secondary": {"car_body_mass": 4000, "k": 2.5e5, "c": 1.2e4}, "static_load": 2e4})",
    R"({"bodies": [
          {"name": "wheel", "mass": 900, "transforms": [{"type": "tz", "value": -0.46, "dof": "z_w"}]},
          {"name": "bogie", "mass": 700, "transforms": [{"type": "tz", "value": -0.8, "dof": "z_b"}]},
          {"name": "car_body", "mass": 4000, "inertia": 1e5,
           "transforms": [{"type": "tz", "value": -1.9, "dof": "z_c"}]}],
        "elements": [
          {"name": "primary", "body_a": "bogie", "point_a": [0, 0.3], "body_b": "wheel", "k": 1.5e6, "c": 6e3},
          {"name": "secondary", "body_a": "car_body", "body_b": "bogie", "point_b": [0, -0.2],
           "k": 2.5e5, "c": 1.2e4}],
        "wheels": [{"body": "wheel"}],
        "loads": [{"body": "car_body", "point": [0.7, 0], "force": 2e4}]})"};

void expect_same_vehicle(const Pair& p) {
  TestVehicle qc("quarter_car", p.quarter_car);
  TestVehicle mbs("mbs", p.mbs);
  ASSERT_EQ(qc.dofs(), mbs.dofs());
  ASSERT_EQ(mbs.wheel_count(), 1);
  EXPECT_EQ(mbs.wheels()[0].offset, 0.0);
  // Relative tolerance 1e-10: both evaluate the same expressions; differences are round-off of
  // sums of terms up to ~1e5 N (ulp ~1e-11 N), far below 1e-10 of the largest entry.
  const auto close = [](const auto& a, const auto& b) {
    return (a - b).cwiseAbs().maxCoeff() <= 1e-10 * (a.cwiseAbs().maxCoeff() + 1e-300);
  };
  for (int trial = 0; trial < 5; ++trial) {
    const VectorXd q = 0.01 * VectorXd::Random(qc.dofs());
    const VectorXd qd = 0.5 * VectorXd::Random(qc.dofs());
    EXPECT_TRUE(close(qc.mass(q), mbs.mass(q))) << qc.mass(q) << "\n\n" << mbs.mass(q);
    EXPECT_TRUE(close(qc.forces(q, qd), mbs.forces(q, qd))) << qc.forces(q, qd).transpose() << "\n"
                                                            << mbs.forces(q, qd).transpose();
    MatrixXd k1, c1, k2, c2;
    qc.tangent(q, qd, k1, c1);
    mbs.tangent(q, qd, k2, c2);
    EXPECT_TRUE(close(k1, k2)) << k1 << "\n\n" << k2;
    EXPECT_TRUE(close(c1, c2)) << c1 << "\n\n" << c2;
    VectorXd z1, z2;
    MatrixXd j1, j2;
    qc.wheel_kinematics(q, z1, j1);
    mbs.wheel_kinematics(q, z2, j2);
    EXPECT_TRUE(close(z1, z2));
    EXPECT_TRUE(close(j1, j2));
  }
  const VectorXd f1 = rigid_rail_frequencies_hz(qc, VectorXd::Zero(qc.dofs()));
  const VectorXd f2 = rigid_rail_frequencies_hz(mbs, VectorXd::Zero(qc.dofs()));
  EXPECT_TRUE(close(f1, f2)) << f1.transpose() << "\n" << f2.transpose();
}

TEST(MbsQuarterCar, TwoMassChainIsTheSameVehicle) {
  expect_same_vehicle(kTwoMass);
}

TEST(MbsQuarterCar, ThreeMassChainIsTheSameVehicle) {
  expect_same_vehicle(kThreeMass);
}

}  // namespace
}  // namespace rumble::test
