// DivergenceMonitor (run/divergence_monitor.hpp): a footprint displacement beyond the policy's
// factor times the static one stops a run that asked to stop and only warns otherwise; a
// velocity beyond 10 m/s is treated alike; a displacement beyond 1 m or a value that is not finite
// stops every run; each with the footprint, the value and the time the motion first passed twice
// its static value. A soil with no static load (a prescribed-load coupler) has no factor bound.
#include "run/divergence_monitor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.hpp"

namespace rumble {
namespace {

using ::testing::HasSubstr;

DivergenceMonitor monitor(bool stop) {
  scenario::DivergenceSpec policy;
  policy.stop = stop;
  return DivergenceMonitor(policy);
}

std::string message_of(DivergenceMonitor& m, const std::vector<double>& u,
                       const std::vector<double>& v, double t) {
  try {
    m.check(0, u.data(), v.data(), u.size(), t, 1e-3);
  } catch (const RunError& e) {
    return e.what();
  }
  return "";
}

TEST(DivergenceMonitor, DisplacementBeyondTheFactorStopsOrWarnsAsAsked) {
  const std::vector<double> rest{1e-4, 2e-4}, still{0.0, 0.0};
  DivergenceMonitor stopping = monitor(true), going_on = monitor(false);
  stopping.watch("soil", rest.data(), 2);
  going_on.watch("soil", rest.data(), 2);
  EXPECT_EQ(message_of(stopping, {3e-4, 5e-4}, still, 0.1), "");  // 2.5 x: onset only
  EXPECT_FALSE(stopping.detected());
  const std::string m = message_of(stopping, {3e-4, 5e-3}, still, 0.2);  // 25 x
  EXPECT_THAT(m, HasSubstr("diverged at t = 0.2 s: soil footprint 1 displacement is 0.005 m"));
  EXPECT_THAT(m, HasSubstr("it first passed 2 x at t = 0.1 s"));
  EXPECT_EQ(message_of(going_on, {3e-4, 5e-3}, still, 0.2), "");  // warned, goes on
  EXPECT_TRUE(going_on.detected());
}

TEST(DivergenceMonitor, AVelocityNoTrainMakesIsADivergence) {
  // Jacobi at 1 ms on the soft FEM soil ran away in velocity (17.7 m/s) at 6 mm, within 20 x.
  const std::vector<double> rest{4e-3, 4e-3};
  DivergenceMonitor stopping = monitor(true), going_on = monitor(false);
  stopping.watch("soil", rest.data(), 2);
  going_on.watch("soil", rest.data(), 2);
  EXPECT_EQ(message_of(stopping, {5e-3, 6e-3}, {0.4, -9.9}, 0.4), "");
  const std::string m = message_of(stopping, {5e-3, 9e-3}, {0.4, -17.7}, 0.5);
  EXPECT_THAT(m, HasSubstr("diverged at t = 0.5 s: soil footprint 1 velocity is -17.7 m/s, more "
                           "than 10 m/s; a footprint first passed 2 x its static displacement at "
                           "t = 0.5 s"));
  EXPECT_THAT(m, HasSubstr("set /coupling/divergence/action to \"continue\""));
  EXPECT_EQ(message_of(going_on, {5e-3, 6e-3}, {0.4, -17.7}, 0.5), "");  // warned, goes on
  EXPECT_TRUE(going_on.detected());
  // Not finite: every run stops.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  DivergenceMonitor again = monitor(false);
  again.watch("soil", rest.data(), 2);
  EXPECT_THAT(message_of(again, {5e-3, 6e-3}, {nan, 0.0}, 0.1),
              HasSubstr("soil footprint 0 velocity is nan"));
}

TEST(DivergenceMonitor, ADisplacementNoTrainMakesStopsEveryRun) {
  const std::vector<double> rest{0.1, 0.1}, still{0.0, 0.0};  // a soft soil: 20 x is 2 m
  DivergenceMonitor going_on = monitor(false);
  going_on.watch("soil", rest.data(), 2);
  EXPECT_THAT(message_of(going_on, {0.1, 1.5}, still, 0.3),
              HasSubstr("displacement is 1.5 m (limit 1 m)"));
}

TEST(DivergenceMonitor, NoStaticLoadLeavesTheFactorOutAndKeepsTheLimits) {
  // A prescribed load on a soil with nothing static on it (a 1 kg wheel: 3e-8 m): 1e-4 m is
  // 3000 x the settlement, Lamb's problem, not a divergence; the limits still hold.
  const std::vector<double> rest{3e-8, 1e-8}, still{0.0, 0.0};
  DivergenceMonitor m = monitor(true);
  m.watch("soil", rest.data(), 2);
  EXPECT_EQ(message_of(m, {1e-4, 4e-5}, {0.02, 0.01}, 0.01), "");
  EXPECT_FALSE(m.detected());
  EXPECT_TRUE(m.summary()["displacement_bound_m"].is_null());
  EXPECT_TRUE(m.summary()["t_first_beyond_twice_static_s"].is_null());
  EXPECT_THAT(message_of(m, {1e-4, 4e-5}, {12.0, 0.01}, 0.02),
              HasSubstr("soil footprint 0 velocity is 12 m/s, more than 10 m/s"));
  DivergenceMonitor hard = monitor(false);
  hard.watch("soil", still.data(), 2);  // exactly nothing static
  EXPECT_EQ(message_of(hard, {0.5, 0.0}, still, 0.01), "");
  EXPECT_THAT(message_of(hard, {1.5, 0.0}, still, 0.02),
              HasSubstr("displacement is 1.5 m (limit 1 m)"));
  // A train's settlement keeps the factor: 20 x 1e-5 m.
  DivergenceMonitor train = monitor(true);
  const std::vector<double> settled{1e-5, 2e-6};
  train.watch("soil", settled.data(), 2);
  EXPECT_DOUBLE_EQ(train.summary()["displacement_bound_m"].get<double>(), 2e-4);
  EXPECT_THAT(message_of(train, {3e-4, 0.0}, still, 0.01),
              HasSubstr("more than 20 x its largest static displacement (1e-05 m)"));
}

}  // namespace
}  // namespace rumble
