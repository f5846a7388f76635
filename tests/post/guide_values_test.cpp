// DIN 4150-3 and BS 7385-2 guide values: the table values at the band edges, the linear
// interpolation inside the bands, the ends, and the PPV / guide ratio. The values are exact
// table numbers, so the checks are to rounding (1e-12 m/s).
#include "post/guide_values.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rumble::post {
namespace {

constexpr double kMm = 1e-3;  // m/s per mm/s
constexpr double kTol = 1e-12;

struct Row {
  double f, line1, line2, line3;  // Hz, mm/s
};

TEST(Din4150_3, TableOneAtTheBandEdgesAndBetween) {
  const Row rows[] = {
      {0.5, 20, 5, 3},                                            // below the table: the 1 Hz value
      {1, 20, 5, 3},       {5, 20, 5, 3},     {10, 20, 5, 3},     // band 1-10 Hz: flat
      {30, 30, 10, 5.5},                                          // 10-50 Hz: half way
      {20, 25, 7.5, 4.25},                                        // a quarter of the way
      {50, 40, 15, 8},     {75, 45, 17.5, 9}, {100, 50, 20, 10},  // 50-100 Hz
      {250, 50, 20, 10},                                          // above: the 100 Hz value
  };
  for (const Row& r : rows) {
    EXPECT_NEAR(din4150_3_guide(Din4150Line::kCommercial, r.f), r.line1 * kMm, kTol) << r.f;
    EXPECT_NEAR(din4150_3_guide(Din4150Line::kDwelling, r.f), r.line2 * kMm, kTol) << r.f;
    EXPECT_NEAR(din4150_3_guide(Din4150Line::kSensitive, r.f), r.line3 * kMm, kTol) << r.f;
  }
  // Continuous across the band edges.
  for (double edge : {10.0, 50.0}) {
    EXPECT_NEAR(din4150_3_guide(Din4150Line::kDwelling, edge * (1 - 1e-9)),
                din4150_3_guide(Din4150Line::kDwelling, edge * (1 + 1e-9)), 1e-6 * kMm);
  }
}

TEST(Bs7385_2, TableOneLinesAndTheDisplacementLimit) {
  for (double f : {1.0, 4.0, 15.0, 40.0, 100.0})
    EXPECT_NEAR(bs7385_2_guide(Bs7385Line::kReinforced, f), 50 * kMm, kTol) << f;
  const std::pair<double, double> line2[] = {{4, 15},    {9.5, 17.5}, {15, 20},
                                             {27.5, 35}, {40, 50},    {80, 50}};
  for (const auto& [f, v] : line2)
    EXPECT_NEAR(bs7385_2_guide(Bs7385Line::kUnreinforced, f), v * kMm, kTol) << f;
  // Below 4 Hz: 0.6 mm zero to peak, as a velocity 2 pi f x.
  EXPECT_NEAR(bs7385_2_guide(Bs7385Line::kUnreinforced, 2.0), 2 * std::numbers::pi * 2 * 0.6e-3,
              kTol);
  // The two parts of line 2 meet at 4 Hz to 0.53 % (15.08 against 15 mm/s).
  EXPECT_NEAR(bs7385_2_guide(Bs7385Line::kUnreinforced, 4.0 - 1e-9) / (15 * kMm), 1.0053, 1e-4);
}

TEST(GuideValues, RatioIsPpvOverGuide) {
  const GuideCheck din = check_din4150_3(Din4150Line::kDwelling, 7.5 * kMm, 30.0);
  EXPECT_NEAR(din.guide, 10 * kMm, kTol);
  EXPECT_NEAR(din.ratio, 0.75, 1e-12);
  const GuideCheck bs = check_bs7385_2(Bs7385Line::kUnreinforced, 40 * kMm, 15.0);
  EXPECT_NEAR(bs.ratio, 2.0, 1e-12);
  EXPECT_EQ(name(Din4150Line::kSensitive), "DIN 4150-3 line 3");
  EXPECT_EQ(name(Bs7385Line::kReinforced), "BS 7385-2 line 1");
}

TEST(GuideValues, FrequencyMustBePositive) {
  for (double f : {0.0, -3.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(din4150_3_guide(Din4150Line::kDwelling, f), std::invalid_argument) << f;
    EXPECT_THROW(bs7385_2_guide(Bs7385Line::kUnreinforced, f), std::invalid_argument) << f;
  }
}

}  // namespace
}  // namespace rumble::post
