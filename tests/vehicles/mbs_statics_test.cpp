// Static wheel loads of mbs vehicles on a rigid rail (Lagrange multipliers of z_w(q) = 0) against
// the weight shares given by statics alone. Two-stage vehicles whose car body rests on two
// bogies and each bogie on two wheelsets are statically determinate, so the loads do not depend
// on the stiffnesses. Tolerance 1e-6 relative: the Newton solution is an equilibrium to ~1e-12
// of the weight, so any larger difference is a modelling error, not numerical noise.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rigid_rail.hpp"
#include "vehicle_harness.hpp"

namespace rumble::test {
namespace {

constexpr double kG = 9.81;  // m/s^2, gravity of the shipped files and the default

TEST(MbsStatics, HalfTrainWheelsEachCarryAQuarterOfTheWeight) {
  TestVehicle v("mbs", R"({"file": "half_train.json"})");
  ASSERT_EQ(v.dofs(), 10);
  ASSERT_EQ(v.wheel_count(), 4);
  const double weight = (16000 + 2 * 1307.5 + 4 * 906.5) * kG;  // N, one side
  const Equilibrium e = rigid_rail_statics(v);
  for (Eigen::Index w = 0; w < 4; ++w) {
    EXPECT_NEAR(e.contact_force(w), weight / 4, 1e-6 * weight / 4) << "wheel " << w;
  }
  // The shipped preloads equal the static element forces, so the nominal geometry is the
  // static one: |q| stays at round-off (residual / stiffness ~ 1e-12 m).
  EXPECT_LT(e.q.cwiseAbs().maxCoeff(), 1e-9);
  const VectorXd forces = v.outputs(e.q, VectorXd::Zero(10));
  ASSERT_EQ(forces.size(), 6);
  EXPECT_NEAR(forces(0), 16000 * kG / 2, 1e-6);                      // secondary_front
  EXPECT_NEAR(forces(2), (16000 * kG / 2 + 1307.5 * kG) / 2, 1e-6);  // primary_1
}

TEST(MbsStatics, HalfTrainWheelOffsetsAreTheWheelsetPositions) {
  TestVehicle v("mbs", R"({"file": "half_train.json"})");
  const double expected[] = {10.78, 8.22, -8.22, -10.78};  // m: bogies +-9.5, semi-wheelbase 1.28
  for (Eigen::Index w = 0; w < 4; ++w) {
    EXPECT_NEAR(v.wheels()[w].offset, expected[w], 1e-12);
    EXPECT_EQ(v.wheels()[w].radius, 0.46);
  }
}

TEST(MbsStatics, TramWheelsEachCarryASixthOfTheWeight) {
  // Three bogies make the car body statically indeterminate; the shipped equal preloads make
  // the nominal geometry an equilibrium with equal bogie loads, and the equilibrium is unique.
  TestVehicle v("mbs", R"({"file": "tram_t2000.json"})");
  ASSERT_EQ(v.dofs(), 14);
  ASSERT_EQ(v.wheel_count(), 6);
  const double weight = 35700.0 / 2 * kG;  // N: T2000, 35.7 t, one side
  const Equilibrium e = rigid_rail_statics(v);
  for (Eigen::Index w = 0; w < 6; ++w) {
    EXPECT_NEAR(e.contact_force(w), weight / 6, 1e-6 * weight / 6) << "wheel " << w;
  }
  EXPECT_LT(e.q.cwiseAbs().maxCoeff(), 1e-9);
}

// A half-train whose car-body centre of mass lies e ahead of the middle, with a payload P at x_p.
// Every point of the car body and bogies lies at its centre-of-mass height, so pitching scales
// all lever arms by cos(theta) and the lever rule holds exactly in the deformed state too.
// No preloads: the car body sags and pitches.
constexpr double kA = 9.0;     // m, bogie centres at +-a
constexpr double kB = 1.25;    // m, semi-wheelbase
constexpr double kE = 0.7;     // m, car-body centre of mass ahead of the middle
constexpr double kXp = -4.0;   // m, payload position
constexpr double kP = 3.0e4;   // N, payload
constexpr double kMc = 15000;  // kg
constexpr double kMb = 1300;   // kg
constexpr double kMw = 900;    // kg

std::string asymmetric_half_train() {
  const auto n = [](double x) { return std::to_string(x); };
  return R"({"bodies": [
      {"name": "car_body", "mass": )" +
         n(kMc) + R"(, "inertia": 9e5, "transforms": [
        {"type": "tx", "value": )" +
         n(kE) + R"(}, {"type": "tz", "value": -1.8, "dof": "zc"},
        {"type": "ry", "dof": "pc"}]},
      {"name": "bogie_f", "mass": )" +
         n(kMb) + R"(, "inertia": 700, "transforms": [
        {"type": "tx", "value": )" +
         n(kA) + R"(}, {"type": "tz", "value": -0.6, "dof": "zf"},
        {"type": "ry", "dof": "pf"}]},
      {"name": "bogie_r", "mass": )" +
         n(kMb) + R"(, "inertia": 700, "transforms": [
        {"type": "tx", "value": )" +
         n(-kA) + R"(}, {"type": "tz", "value": -0.6, "dof": "zr"},
        {"type": "ry", "dof": "pr"}]},
      {"name": "ws1", "mass": )" +
         n(kMw) + R"(, "parent": "bogie_f", "transforms": [
        {"type": "ry", "value": 0}, {"type": "tx", "value": )" +
         n(kB) + R"(}]},
      {"name": "ws2", "mass": )" +
         n(kMw) + R"(, "transforms": [
        {"type": "tx", "value": )" +
         n(kA - kB) + R"(}, {"type": "tz", "value": -0.46, "dof": "z2"}]},
      {"name": "ws3", "mass": )" +
         n(kMw) + R"(, "transforms": [
        {"type": "tx", "value": )" +
         n(-kA + kB) + R"(}, {"type": "tz", "value": -0.46, "dof": "z3"}]},
      {"name": "ws4", "mass": )" +
         n(kMw) + R"(, "transforms": [
        {"type": "tx", "value": )" +
         n(-kA - kB) + R"(}, {"type": "tz", "value": -0.46, "dof": "z4"}]}],
    "elements": [
      {"body_a": "car_body", "point_a": [)" +
         n(kA - kE) + R"(, 0], "body_b": "bogie_f", "k": 4e5, "c": 1e4},
      {"body_a": "car_body", "point_a": [)" +
         n(-kA - kE) + R"(, 0], "body_b": "bogie_r", "k": 4e5, "c": 1e4},
      {"body_a": "bogie_f", "point_a": [)" +
         n(-kB) + R"(, 0], "body_b": "ws2", "k": 1.2e6},
      {"body_a": "bogie_r", "point_a": [)" +
         n(kB) + R"(, 0], "body_b": "ws3", "k": 1.2e6},
      {"body_a": "bogie_r", "point_a": [)" +
         n(-kB) + R"(, 0], "body_b": "ws4", "k": 1.2e6}],
    "wheels": [{"body": "ws1"}, {"body": "ws2"}, {"body": "ws3"}, {"body": "ws4"}],
    "loads": [{"name": "payload", "body": "car_body", "point": [)" +
         n(kXp - kE) + R"(, 0], "force": )" + n(kP) + R"(}]})";
}

TEST(MbsStatics, AsymmetricCarBodyFollowsTheLeverRule) {
  // ws1 hangs rigidly from the front bogie (no primary spring, no DOF of its own) to exercise
  // parent chains; the bogie's pitch then carries the lever arm +b exactly like a spring would.
  TestVehicle v("mbs", asymmetric_half_train());
  ASSERT_EQ(v.dofs(), 9);
  const Equilibrium e = rigid_rail_statics(v);
  // Car body on two supports at +-a: front share of its weight at e and of the payload at x_p.
  const double front = (kMc * kG * (kA + kE) + kP * (kA + kXp)) / (2 * kA);
  const double rear = kMc * kG + kP - front;
  const double expected[] = {(front + kMb * kG) / 2 + kMw * kG, (front + kMb * kG) / 2 + kMw * kG,
                             (rear + kMb * kG) / 2 + kMw * kG, (rear + kMb * kG) / 2 + kMw * kG};
  for (Eigen::Index w = 0; w < 4; ++w) {
    EXPECT_NEAR(e.contact_force(w), expected[w], 1e-6 * expected[w]) << "wheel " << w;
  }
  EXPECT_GT(std::abs(e.q(1)), 1e-5);  // the car body did pitch: the check is not trivial
}

}  // namespace
}  // namespace rumble::test
