// Peak particle velocity of synthetic signals whose peaks are known in closed form, and the
// PPV-versus-distance ordering.
#include "post/ppv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace rumble::post {
namespace {

// A Ricker wavelet (the second derivative of a Gaussian) of peak A at t_c, sampled so that t_c
// is a sample: the peak is hit exactly, so PPV = A to rounding (1e-15 relative; 1e-12 allowed).
TEST(Ppv, RickerPulsePeakIsItsAmplitude) {
  const double a = 3.2e-3, f = 25.0, dt = 1e-4, tc = 0.4;  // m/s, Hz, s, s
  std::vector<double> v(8000);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const double x = std::numbers::pi * f * (static_cast<double>(k) * dt - tc);
    v[k] = -a * (1.0 - 2.0 * x * x) * std::exp(-x * x);  // negative-going: |min| is the peak
  }
  const Peak p = peak_abs(v);
  EXPECT_NEAR(p.value, a, 1e-12 * a);
  EXPECT_EQ(p.index, 4000u);
}

// A sine sampled off its crests: the PPV is the largest sample, A cos(pi f dt) at worst, never A.
TEST(Ppv, SampledSineReadsTheLargestSample) {
  const double a = 1e-3, f = 16.0, dt = 1.0 / 1000.0;
  std::vector<double> v(1000);
  double largest = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    v[k] = a * std::sin(2.0 * std::numbers::pi * f * static_cast<double>(k) * dt + 0.3);
    largest = std::max(largest, std::abs(v[k]));
  }
  EXPECT_DOUBLE_EQ(peak_abs(v).value, largest);
  EXPECT_GE(largest, a * std::cos(std::numbers::pi * f * dt));
  EXPECT_LE(largest, a);
}

// Circular motion in the horizontal plane plus a vertical pulse: each component's peak is A
// (or B), the vector sum's is sqrt(A^2 + B^2) where the pulse meets the circle.
TEST(Ppv, ThreeComponentIsTheLargestVectorMagnitude) {
  const double a = 2e-3, b = 1.5e-3, f = 10.0, dt = 1e-3;
  const std::size_t n = 2000, pulse = 1234;
  std::vector<double> vx(n), vy(n), vz(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double w = 2.0 * std::numbers::pi * f * static_cast<double>(k) * dt;
    vx[k] = a * std::cos(w);
    vy[k] = a * std::sin(w);
  }
  vz[pulse] = -b;
  const Peak p = peak_vector(vx, vy, vz);
  EXPECT_NEAR(p.value, std::hypot(a, b), 1e-15);
  EXPECT_EQ(p.index, pulse);
  EXPECT_NEAR(peak_abs(vx).value, a, 1e-15);
  EXPECT_DOUBLE_EQ(peak_abs(vz).value, b);
}

// The vector sum is never below any component's peak (random signals, exact inequality).
TEST(Ppv, ThreeComponentBoundsEveryComponent) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1e-3);
  std::vector<double> vx(500), vy(500), vz(500);
  for (std::size_t k = 0; k < 500; ++k) vx[k] = g(rng), vy[k] = g(rng), vz[k] = g(rng);
  const double p3 = peak_vector(vx, vy, vz).value;
  for (const auto* v : {&vx, &vy, &vz}) EXPECT_GE(p3, peak_abs(*v).value);
}

TEST(Ppv, NanIsReportedNotSkipped) {
  std::vector<double> v = {0.1, -0.5, std::numeric_limits<double>::quiet_NaN(), 2.0};
  const Peak p = peak_abs(v);
  EXPECT_TRUE(std::isnan(p.value));
  EXPECT_EQ(p.index, 2u);
  EXPECT_EQ(peak_abs(std::vector<double>{}).value, 0.0);
}

TEST(Ppv, VectorComponentsMustHaveEqualLengths) {
  const std::vector<double> a(3, 0.0), b(4, 0.0);
  EXPECT_THROW(peak_vector(a, a, b), std::invalid_argument);
}

TEST(Ppv, VersusDistanceIsOrderedByDistanceThenDepth) {
  const std::vector<ReceiverPpv> in = {{"far", 10.0, 0.0, 1e-4, 2e-4},
                                       {"near deep", 2.5, 1.0, 5e-4, 6e-4},
                                       {"near", 2.5, 0.0, 9e-4, 1e-3},
                                       {"mid", 5.0, 0.0, 3e-4, 4e-4}};
  const std::vector<ReceiverPpv> out = ppv_versus_distance(in);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].name, "near");
  EXPECT_EQ(out[1].name, "near deep");
  EXPECT_EQ(out[2].name, "mid");
  EXPECT_EQ(out[3].name, "far");
  EXPECT_DOUBLE_EQ(out[0].ppv_z, 9e-4);
}

}  // namespace
}  // namespace rumble::post
