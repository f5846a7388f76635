// The resolved band's measures (post/resolved_band.hpp): the share of energy above a frequency
// is exact for sines on bins (rectangular spectrum, Parseval), and the zero-phase low-pass passes
// each sine with the 4th-order Butterworth gain 1 / sqrt(1 + (f / f_c)^8), in phase.
#include "post/resolved_band.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "post/ppv.hpp"
#include "post/spectrum.hpp"

namespace rumble::post {
namespace {

constexpr double kBandDt = 1e-3;  // s
constexpr std::size_t kBandN = 1000;

std::vector<double> two_sines(double a1, double f1, double a2, double f2) {
  std::vector<double> x(kBandN);
  for (std::size_t k = 0; k < kBandN; ++k) {
    const double t = static_cast<double>(k) * kBandDt;
    x[k] = a1 * std::sin(2.0 * std::numbers::pi * f1 * t) +
           a2 * std::sin(2.0 * std::numbers::pi * f2 * t);
  }
  return x;
}

double butterworth(double f, double f_c) {
  return 1.0 / std::sqrt(1.0 + std::pow(f / f_c, 2 * kLowPassOrder));
}

TEST(ResolvedBandPost, TheShareAboveIsTheEnergyOfWhatLiesAbove) {
  const std::vector<double> x = two_sines(1.0, 10.0, 2.0, 50.0);  // whole cycles in 1 s
  SpectrumAnalyzer rect(kBandN, Window::kRectangular);
  const Spectrum p = rect.power(x, kBandDt);
  EXPECT_NEAR(energy_share_above(p, 30.0), 4.0 / 5.0, 1e-12);
  EXPECT_NEAR(energy_share_above(p, 5.0), 1.0, 1e-12);
  EXPECT_NEAR(energy_share_above(p, 60.0), 0.0, 1e-12);
  EXPECT_EQ(energy_share_above(rect.power(std::vector<double>(kBandN, 0.0), kBandDt), 30.0), 0.0);
}

TEST(ResolvedBandPost, TheLowPassKeepsTheBandInPhaseAndCutsAbove) {
  const double f_c = 30.0;
  const std::vector<double> x = two_sines(1.0, 10.0, 1.0, 90.0);
  const std::vector<double> y = zero_phase_low_pass(x, kBandDt, f_c);
  const std::vector<double> expected =
      two_sines(butterworth(10.0, f_c), 10.0, butterworth(90.0, f_c), 90.0);
  // Away from the record's ends, where the zero padding cuts the sines off.
  for (std::size_t k = kBandN / 4; k < 3 * kBandN / 4; ++k)
    EXPECT_NEAR(y[k], expected[k], 2e-3) << k;
}

TEST(ResolvedBandPost, ABlowKeepsItsPlaceAndLosesWhatLiesAbove) {
  // A 20 Hz burst at 0.5 s: low-passed at 100 Hz its peak stays at the same sample and height.
  std::vector<double> x(kBandN);
  for (std::size_t k = 0; k < kBandN; ++k) {
    const double s = (static_cast<double>(k) * kBandDt - 0.5) / 0.03;
    x[k] = std::exp(-0.5 * s * s) * std::cos(2.0 * std::numbers::pi * 20.0 * (k * kBandDt - 0.5));
  }
  const std::vector<double> y = zero_phase_low_pass(x, kBandDt, 100.0);
  EXPECT_EQ(peak_abs(y).index, peak_abs(x).index);
  EXPECT_NEAR(peak_abs(y).value, peak_abs(x).value, 1e-3);
  // At 5 Hz, a quarter of the burst's frequency, little is left.
  EXPECT_LT(peak_abs(zero_phase_low_pass(x, kBandDt, 5.0)).value, 0.1);
}

}  // namespace
}  // namespace rumble::post
