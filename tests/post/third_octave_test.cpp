// One-third-octave bands (IEC 61260 base-10 series) and band velocity levels: a sine's level in
// its band is 20 log10((A/sqrt 2) / v_ref), re 1e-9 m/s and in VdB.
#include "post/third_octave.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "post/spectrum.hpp"

namespace rumble::post {
namespace {

std::vector<double> sampled_sine(std::size_t n, double dt, double a, double f) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k)
    x[k] = a * std::sin(2.0 * std::numbers::pi * f * static_cast<double>(k) * dt + 0.7);
  return x;
}

const BandLevel& band(const std::vector<BandLevel>& levels, const std::string& nominal) {
  for (const BandLevel& b : levels)
    if (b.band.nominal == nominal) return b;
  throw std::out_of_range("no band " + nominal);
}

TEST(ThirdOctave, BandsAreTheBaseTenSeries) {
  const ThirdOctaveBand b16 = third_octave_band(12);
  EXPECT_NEAR(b16.centre, 15.8489, 1e-4);
  EXPECT_EQ(b16.nominal, "16");
  EXPECT_NEAR(b16.upper / b16.lower, std::pow(10.0, 0.1), 1e-12);
  EXPECT_NEAR(b16.upper, third_octave_band(13).lower, 1e-12);  // adjacent bands share edges
  EXPECT_EQ(third_octave_band(0).nominal, "1");
  EXPECT_EQ(third_octave_band(5).nominal, "3.15");
  EXPECT_EQ(third_octave_band(15).nominal, "31.5");
  EXPECT_EQ(third_octave_band(18).nominal, "63");
  EXPECT_EQ(third_octave_band(25).nominal, "315");
  EXPECT_EQ(third_octave_band(30).nominal, "1000");
  EXPECT_EQ(third_octave_band(-1).nominal, "0.8");
  EXPECT_EQ(third_octave_band(-13).nominal, "0.05");
  EXPECT_DOUBLE_EQ(third_octave_band(30).centre, 1000.0);
  const std::vector<ThirdOctaveBand> bands = third_octave_bands(1.0, 100.0);
  ASSERT_EQ(bands.size(), 21u);  // 1 Hz .. 100 Hz, both ends included
  EXPECT_EQ(bands.front().nominal, "1");
  EXPECT_EQ(bands.back().nominal, "100");
  // The ends are nominal: 1 to 250 Hz (the default) ends with the 250 Hz band, whose centre is
  // 251.19 Hz (it stopped at 200 Hz, issue #29), and 31.5 Hz starts with the 31.5 Hz band.
  EXPECT_EQ(third_octave_bands(1.0, 250.0).back().nominal, "250");
  EXPECT_EQ(third_octave_bands(1.0, 250.0).size(), 25u);
  EXPECT_EQ(third_octave_bands(31.5, 63.0).front().nominal, "31.5");
  EXPECT_EQ(third_octave_bands(1.0, 240.0).back().nominal, "200");
  EXPECT_THROW(third_octave_bands(0.0, 10.0), std::invalid_argument);
}

// A record of 1 s at 1 kHz (bins 1 Hz apart, Nyquist 500 Hz) resolves the bands at least a bin
// wide (f_m >= 4.3 Hz: the 5 Hz band, 1.16 Hz wide, is in; 4 Hz, 0.93 Hz wide, is out) and below
// Nyquist (the 400 Hz band, up to 447 Hz, is in; 500 Hz, up to 561 Hz, is out).
TEST(ThirdOctave, ResolvedBandsHoldABinAndStayBelowNyquist) {
  const std::vector<ThirdOctaveBand> r =
      resolved_bands(third_octave_bands(1.0, 1000.0), 1000, 1e-3);
  ASSERT_FALSE(r.empty());
  EXPECT_EQ(r.front().nominal, "5");
  EXPECT_EQ(r.back().nominal, "400");
}

// A 16 Hz sine of 1 mm/s amplitude on a bin (10 s record: bins 0.1 Hz): all its power is in one
// bin, so its band reads 20 log10((A/sqrt 2)/v_ref) to rounding: 116.99 dB re 1e-9 m/s and
// 88.89 VdB (docs/physics.md §10 case 11: 88.9). 1e-9 dB allowed; the next bands are empty (-inf
// would mean exactly 0; rounding leaves < -100 dB below the tone).
TEST(ThirdOctave, SineLevelInItsBand) {
  const std::size_t n = 10000;
  const double dt = 1e-3, a = 1e-3;
  SpectrumAnalyzer rect(n, Window::kRectangular);
  const Spectrum p = rect.power(sampled_sine(n, dt, a, 16.0), dt);
  const std::vector<ThirdOctaveBand> bands = third_octave_bands(1.0, 250.0);
  const double expected = 20.0 * std::log10(a / std::sqrt(2.0) / kVelocityRefIso1683);
  EXPECT_NEAR(expected, 116.99, 5e-3);
  const auto iso = band_levels(p, bands, kVelocityRefIso1683);
  EXPECT_NEAR(band(iso, "16").level, expected, 1e-9);
  EXPECT_NEAR(band(iso, "16").rms, a / std::sqrt(2.0), 1e-15);
  EXPECT_LT(band(iso, "12.5").level, expected - 100.0);
  EXPECT_LT(band(iso, "20").level, expected - 100.0);
  const auto vdb = band_levels(p, bands, kVelocityRefVdb);
  EXPECT_NEAR(band(vdb, "16").level, 20.0 * std::log10(a / std::sqrt(2.0) / 2.54e-8), 1e-9);
  EXPECT_NEAR(band(vdb, "16").level, 88.89, 5e-3);
}

// Off a bin (16.05 Hz) the rectangular window leaks: the power outside the band is at most
// about 2 / (pi^2 m) of the tone's for m bins to the nearest band edge (m = 17 here: 1.2 %), so
// the band reads low by < 0.06 dB; 0.1 dB allowed.
TEST(ThirdOctave, OffBinSineLevelWithinLeakageBound) {
  const std::size_t n = 10000;
  const double dt = 1e-3, a = 1e-3;
  SpectrumAnalyzer rect(n, Window::kRectangular);
  const auto levels = band_levels(rect.power(sampled_sine(n, dt, a, 16.05), dt),
                                  third_octave_bands(10.0, 25.0), kVelocityRefIso1683);
  const double expected = 20.0 * std::log10(a / std::sqrt(2.0) / kVelocityRefIso1683);
  EXPECT_NEAR(band(levels, "16").level, expected, 0.1);
  EXPECT_LE(band(levels, "16").level, expected + 1e-9);
}

// Two sines in different bands each keep their own level; in one band their powers add.
TEST(ThirdOctave, PowersAddWithinABand) {
  const std::size_t n = 10000;
  const double dt = 1e-3;
  std::vector<double> x = sampled_sine(n, dt, 1e-3, 40.0);
  const std::vector<double> y = sampled_sine(n, dt, 2e-3, 42.0),
                            z = sampled_sine(n, dt, 5e-4, 100.0);
  for (std::size_t k = 0; k < n; ++k) x[k] += y[k] + z[k];
  SpectrumAnalyzer rect(n, Window::kRectangular);
  const auto levels =
      band_levels(rect.power(x, dt), third_octave_bands(30.0, 130.0), kVelocityRefIso1683);
  EXPECT_NEAR(band(levels, "40").rms, std::sqrt((1e-6 + 4e-6) / 2.0), 1e-15);
  EXPECT_NEAR(band(levels, "100").rms, 5e-4 / std::sqrt(2.0), 1e-15);
}

TEST(ThirdOctave, LevelOfNothingAndBadReference) {
  EXPECT_EQ(level_db(0.0, 1e-9), -std::numeric_limits<double>::infinity());
  EXPECT_NEAR(level_db(1e-3, 1e-9), 120.0, 1e-12);  // 1 mm/s RMS = 120 dB re 1e-9 m/s
  EXPECT_THROW(level_db(1e-3, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace rumble::post
