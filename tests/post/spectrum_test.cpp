// One-sided spectra with FFTW: the documented scalings (a sine of amplitude A reads A at its
// frequency with the Hann window; power sums to the mean square), the Hann scalloping bound,
// and the dominant frequency.
#include "post/spectrum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "post/fft.hpp"

namespace rumble::post {
namespace {

std::vector<double> sine(std::size_t n, double dt, double a, double f, double phase = 0.3) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k)
    x[k] = a * std::sin(2.0 * std::numbers::pi * f * static_cast<double>(k) * dt + phase);
  return x;
}

std::size_t argmax(const std::vector<double>& v) {
  return static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
}

TEST(FftSize, FriendlyLengthsHaveOnlySmallFactors) {
  EXPECT_EQ(fft_friendly_size(1), 1u);
  EXPECT_EQ(fft_friendly_size(11), 12u);
  EXPECT_EQ(fft_friendly_size(1000), 1000u);
  EXPECT_EQ(fft_friendly_size(1021), 1024u);  // 1021 prime, 1022 = 2 * 7 * 73, 1023 = 3 * 11 * 31
}

// Bin-centred sine (50 Hz = bin 50 of N = 1000 at 1 kHz), Hann window: A_k = A exactly in exact
// arithmetic (the negative-frequency image is 100 bins away, where the Hann window's transform
// is exactly 0 for integer bins); 1e-9 relative leaves room for rounding only.
TEST(Spectrum, BinCentredSineReadsItsAmplitude) {
  const std::size_t n = 1000;
  const double dt = 1e-3, a = 2.5e-3;
  SpectrumAnalyzer hann(n, Window::kHann);
  const Spectrum s = hann.amplitude(sine(n, dt, a, 50.0), dt);
  EXPECT_DOUBLE_EQ(s.df, 1.0);
  ASSERT_EQ(s.values.size(), n / 2 + 1);
  EXPECT_EQ(argmax(s.values), 50u);
  EXPECT_NEAR(s.values[50], a, 1e-9 * a);
  // The Hann main lobe: the neighbours read A/2, the next ones 0.
  EXPECT_NEAR(s.values[49], a / 2, 1e-9 * a);
  EXPECT_NEAR(s.values[48], 0.0, 1e-9 * a);
  SpectrumAnalyzer rect(n, Window::kRectangular);
  EXPECT_NEAR(rect.amplitude(sine(n, dt, a, 50.0), dt).values[50], a, 1e-9 * a);
}

// Off-bin sines, Hann window: the peak bin reads between the scalloping bound 0.8488 A (half a
// bin off, (2/pi)/(3/4)) and A. At exactly half a bin it reads 0.8488 A to 0.2 % (the image at
// -f and the next sidelobes add at most ~1e-4 at bin 50 of 1000).
TEST(Spectrum, OffBinSineStaysWithinTheHannScallopingLoss) {
  const std::size_t n = 1000;
  const double dt = 1e-3, a = 1e-3, bound = (2.0 / std::numbers::pi) / 0.75;
  SpectrumAnalyzer hann(n, Window::kHann);
  for (double delta : {0.1, 0.25, 0.4, 0.5, 0.6, 0.9}) {
    const Spectrum s = hann.amplitude(sine(n, dt, a, 50.0 + delta), dt);
    const double peak = *std::max_element(s.values.begin(), s.values.end());
    EXPECT_GE(peak, bound * a * (1.0 - 2e-3)) << "delta " << delta;
    EXPECT_LE(peak, a * (1.0 + 2e-3)) << "delta " << delta;
  }
  const Spectrum half = hann.amplitude(sine(n, dt, a, 50.5), dt);
  EXPECT_NEAR(*std::max_element(half.values.begin(), half.values.end()), bound * a,
              2e-3 * bound * a);
}

// Parseval: with the rectangular window the power bins add up to the record's mean square
// (random record, odd and even N: the Nyquist bin is single only for even N). 1e-12 relative.
TEST(Spectrum, RectangularPowerSumsToTheMeanSquare) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1e-3);
  for (std::size_t n : {1000u, 999u}) {
    std::vector<double> x(n);
    double ms = 0.0;
    for (double& v : x) {
      v = g(rng) + 2e-4;  // a mean, so the DC bin counts too
      ms += v * v;
    }
    ms /= static_cast<double>(n);
    SpectrumAnalyzer rect(n, Window::kRectangular);
    const Spectrum p = rect.power(x, 1e-3);
    double sum = 0.0;
    for (double v : p.values) sum += v;
    EXPECT_NEAR(sum, ms, 1e-12 * ms) << "n = " << n;
  }
}

// Hann power is energy-corrected: an off-bin sine's bins add up to A^2/2 (the mean square). The
// image at -f leaks at most ~1e-4 of it here, so 0.1 %.
TEST(Spectrum, HannPowerOfASineIsItsMeanSquare) {
  const std::size_t n = 2000;
  const double dt = 1e-3, a = 1e-3;
  SpectrumAnalyzer hann(n, Window::kHann);
  const Spectrum p = hann.power(sine(n, dt, a, 37.3), dt);
  double sum = 0.0;
  for (double v : p.values) sum += v;
  EXPECT_NEAR(sum, a * a / 2, 1e-3 * a * a / 2);
}

// The dominant frequency of a sine at any offset from the bins (a sweep of 21 offsets over one
// bin): within 0.025 bin. The Gaussian (log-parabola) fit through three Hann-windowed bins is off
// by at most 0.016 bin over a 101-offset sweep; a parabola through the magnitudes would be off
// by 0.053 bin and fail here.
TEST(Spectrum, DominantFrequencyOfAnOffBinSine) {
  const std::size_t n = 1000;
  const double dt = 1e-3;
  SpectrumAnalyzer hann(n, Window::kHann);
  for (int i = 0; i <= 20; ++i) {
    const double f = 30.0 + 0.05 * i;
    const Spectrum s = hann.amplitude(sine(n, dt, 1e-3, f), dt);
    EXPECT_NEAR(dominant_frequency(s, 1.0), f, 0.025 * s.df) << f;
  }
}

// Below f_min nothing counts (a large 0.5 Hz sway does not hide a 20 Hz component), and a
// silent record has no dominant frequency.
TEST(Spectrum, DominantFrequencyIgnoresWhatIsBelowFmin) {
  const std::size_t n = 4000;
  const double dt = 1e-3;
  std::vector<double> x = sine(n, dt, 1e-2, 0.5);
  const std::vector<double> y = sine(n, dt, 1e-4, 20.0);
  for (std::size_t k = 0; k < n; ++k) x[k] += y[k];
  SpectrumAnalyzer hann(n, Window::kHann);
  EXPECT_NEAR(dominant_frequency(hann.amplitude(x, dt), 1.0), 20.0, 0.01);
  EXPECT_TRUE(std::isnan(dominant_frequency(hann.amplitude(std::vector<double>(n, 0.0), dt), 1.0)));
}

TEST(Spectrum, RecordOfTheWrongLengthIsRefused) {
  SpectrumAnalyzer hann(100, Window::kHann);
  EXPECT_THROW(hann.amplitude(std::vector<double>(99, 0.0), 1e-3), std::invalid_argument);
  EXPECT_THROW(hann.amplitude(std::vector<double>(100, 0.0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace rumble::post
