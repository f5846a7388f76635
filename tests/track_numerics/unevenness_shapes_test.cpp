// Deterministic unevenness: none, cosine dip and bump (peak, support, continuity) and the wheel
// flat (depth L^2/(16R), period 2 pi R of rolled distance, phase, wheel selection).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "scenario/scenario_schema.hpp"
#include "track/unevenness.hpp"

namespace rumble {
namespace {

using nlohmann::json;
const std::vector<double> kRadii = {0.46, 0.42};  // two wheels

Unevenness make(const json& spec) {
  return Unevenness(UnevennessSpec::from_json(scenario::unevenness_with_defaults(spec)), kRadii,
                    -0.6, 60.0);
}

TEST(UnevennessShapes, NoneIsSmooth) {
  // (An absent unevenness is {"type": "none"} once validated: ScenarioValidate tests it.)
  const Unevenness u = make(json::parse(R"({"type": "none"})"));
  for (double x : {-0.6, 0.0, 3.3, 60.0}) EXPECT_EQ(u.at(0, x, x), 0.0);
}

TEST(UnevennessShapes, DipIsARaisedCosineOfGivenDepthAndSupport) {
  const double centre = 12.0, length = 0.5, depth = 2e-3;
  const Unevenness u =
      make({{"type", "dip"}, {"position", centre}, {"length", length}, {"depth", depth}});
  // Peak (positive: a dip, z down) at the centre, half depth at the quarter points.
  EXPECT_DOUBLE_EQ(u.at(0, centre, 0.0), depth);
  EXPECT_NEAR(u.at(0, centre - 0.25 * length, 0.0), 0.5 * depth, 1e-15);
  EXPECT_NEAR(u.at(1, centre + 0.25 * length, 0.0), 0.5 * depth, 1e-15);
  // Support [centre - L/2, centre + L/2]: zero on and outside the ends.
  for (double x :
       {centre - 0.5 * length, centre + 0.5 * length, centre - 0.26, centre + 0.3, 0.0, 59.0})
    EXPECT_EQ(u.at(0, x, 0.0), 0.0) << x;
  // Inside: positive, symmetric, maximal at the centre, and (1 - cos)/2 with x0 = centre - L/2.
  for (double s = 0.01; s < 0.5 * length; s += 0.01) {
    const double x0 = centre - 0.5 * length, x = centre + s;
    EXPECT_GT(u.at(0, centre - s, 0.0), 0.0);
    EXPECT_NEAR(u.at(0, centre - s, 0.0), u.at(0, centre + s, 0.0), 1e-15);
    EXPECT_NEAR(u.at(0, x, 0.0),
                depth * 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * (x - x0) / length)), 1e-15);
    EXPECT_LE(u.at(0, x, 0.0), depth);
  }
  // C1 at the ends: r(end - h) = depth sin^2(pi h / L) ~ depth (pi h / L)^2, so the slope
  // r/h -> 0 (a kink would leave r/h finite).
  for (double h : {1e-3, 1e-4, 1e-5}) {
    const double r = u.at(0, centre + 0.5 * length - h, 0.0);
    EXPECT_NEAR(r, depth * std::pow(std::sin(std::numbers::pi * h / length), 2), 1e-12 * depth)
        << h;
    EXPECT_LT(r / h, 2.0 * depth * std::numbers::pi * std::numbers::pi * h / (length * length))
        << h;
  }
}

TEST(UnevennessShapes, BumpIsNegativeAndTheSameForEveryWheel) {
  const Unevenness u =
      make({{"type", "bump"}, {"position", 3.0}, {"length", 0.2}, {"height", 1e-3}});
  EXPECT_DOUBLE_EQ(u.at(0, 3.0, 0.0), -1e-3);
  EXPECT_DOUBLE_EQ(u.at(1, 3.0, 7.0), -1e-3);  // rolled distance plays no part
  EXPECT_NEAR(u.at(0, 2.95, 0.0), -0.5e-3, 1e-15);
  EXPECT_EQ(u.at(1, 3.1, 0.0), 0.0);
  EXPECT_EQ(u.at(1, 2.9, 0.0), 0.0);
}

TEST(UnevennessShapes, WheelFlatDefaultDepthIsLSquaredOver16R) {
  const double L = 0.06, R = kRadii[1];
  const Unevenness u = make({{"type", "wheel_flat"}, {"length", L}, {"wheel", 1}});
  // Default phase: the flat's centre is under the contact after half a turn, pi R.
  EXPECT_DOUBLE_EQ(u.at(1, 5.0, std::numbers::pi * R), L * L / (16.0 * R));
  EXPECT_NEAR(L * L / (16.0 * R), 0.000535714, 1e-9);  // 0.54 mm for 6 cm on R = 0.42 m
}

TEST(UnevennessShapes, WheelFlatRepeatsEveryCircumferenceOfRolledDistance) {
  const double L = 0.05, d = 4e-4, R = kRadii[0], first = 0.3, C = 2.0 * std::numbers::pi * R;
  const Unevenness u =
      make({{"type", "wheel_flat"}, {"length", L}, {"depth", d}, {"first_impact", first}});
  for (int n = 0; n < 40; ++n) {
    const double centre = first + n * C;
    EXPECT_NEAR(u.at(0, 1.0, centre), d, 1e-12 * d) << n;             // full depth at impact
    EXPECT_NEAR(u.at(0, 1.0, centre + 0.25 * L), 0.5 * d, 1e-9 * d);  // cosine shape
    EXPECT_EQ(u.at(0, 1.0, centre - 0.5 * L - 1e-9), 0.0);            // support: L of rolling
    EXPECT_EQ(u.at(0, 1.0, centre + 0.5 * L + 1e-9), 0.0);
    EXPECT_EQ(u.at(0, 1.0, centre + 0.5 * C), 0.0);  // half a turn later
  }
  // The profile as a function of rolled distance has period 2 pi R exactly (up to round-off
  // of the wrap), and nothing else: at 1.01 C it differs.
  for (double s = 0.0; s < C; s += C / 997.0) {
    EXPECT_NEAR(u.at(0, 2.0, s), u.at(0, 2.0, s + C), 1e-9 * d) << s;
    EXPECT_NEAR(u.at(0, 2.0, s), u.at(0, 2.0, s + 25.0 * C), 1e-9 * d) << s;
  }
  EXPECT_GT(std::abs(u.at(0, 2.0, first) - u.at(0, 2.0, first + 1.01 * C)), 0.1 * d);
  // Before the first impact nothing (with the first impact at 0.3 m and L/2 = 2.5 cm).
  EXPECT_EQ(u.at(0, 2.0, 0.0), 0.0);
}

TEST(UnevennessShapes, WheelFlatOnlyOnItsWheelAndIndependentOfPosition) {
  const Unevenness u = make({{"type", "wheel_flat"}, {"length", 0.05}, {"depth", 4e-4}});
  const double at_impact = std::numbers::pi * kRadii[0];
  EXPECT_DOUBLE_EQ(u.at(0, 0.0, at_impact), 4e-4);
  EXPECT_DOUBLE_EQ(u.at(0, 37.0, at_impact), 4e-4);
  EXPECT_EQ(u.at(1, 0.0, at_impact), 0.0);
  EXPECT_EQ(u.at(1, 0.0, std::numbers::pi * kRadii[1]), 0.0);
}

}  // namespace
}  // namespace rumble
