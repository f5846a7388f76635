// Random profile synthesis, statistical properties seen through Unevenness::at() along a track
// shorter than the profile's period (so the result is random): the variance over the track
// averaged over seeds, and a Welch estimate of the PSD in a few bands. Tolerances are derived
// in the tests from the spectrum itself (Gaussian-process variance of the estimators; the
// random-phase model fluctuates less than a Gaussian one, since its line amplitudes are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "simpson_log.hpp"
#include "track/unevenness.hpp"
#include "track_spec/unevenness_psd.hpp"

namespace rumble {
namespace {

UnevennessSpec spec(const char* cls, unsigned seed, double lmin, double lmax) {
  UnevennessSpec s;
  s.kind = UnevennessSpec::Kind::kRandom;
  s.spectrum = cls;
  s.seed = seed;
  s.wavelength_min = lmin;
  s.wavelength_max = lmax;
  return s;
}

TEST(RandomProfileStatistics, VarianceAlongTheTrackAveragedOverSeedsIsThePsdIntegral) {
  // FRA4, wavelengths 1 .. 30 m, track of W = 600 m (the profile's period is 1024 m, so each
  // seed's mean square over the track is a random variable with mean exactly sum A_k^2/2).
  const double lmin = 1.0, lmax = 30.0, x0 = -0.6, x1 = 599.4, W = x1 - x0;
  const RoughnessSpectrum psd = RoughnessSpectrum::fra(4);
  const double w_lo = 2 * std::numbers::pi / lmax, w_hi = 2 * std::numbers::pi / lmin;
  const double sigma2 = psd.integral(w_lo, w_hi);  // m^2
  // Gaussian process, window W >> correlation length: Var(mean square) = (2/W) int R^2 dtau =
  // (2 pi / W) int_0^inf S^2 dOmega for a one-sided S per rad/m.
  const double s2 = simpson_log([&](double w) { return psd(w) * psd(w); }, w_lo, w_hi);
  const double sd_one = std::sqrt(2.0 * std::numbers::pi * s2 / W);
  const int seeds = 24;
  const double tolerance = 4.0 * sd_one / std::sqrt(static_cast<double>(seeds));
  // The test must be able to see the classic errors: factor 2 and factor 2 pi.
  ASSERT_LT(tolerance, 0.25 * sigma2);

  double average = 0.0;
  const std::vector<double> radii = {0.46};
  for (int seed = 0; seed < seeds; ++seed) {
    const Unevenness u(spec("FRA4", static_cast<unsigned>(seed), lmin, lmax), radii, x0, x1);
    // Points off the grid (spacing 1/16 m): linear interpolation loses at most 2.5 % of the
    // 1 m waves' power, < 0.1 % of this spectrum's total, well inside the tolerance.
    double ms = 0.0;
    int n = 0;
    for (double x = x0; x < x1; x += 0.0371, ++n) ms += u.at(0, x, 0.0) * u.at(0, x, 0.0);
    average += ms / n;
  }
  average /= seeds;
  EXPECT_NEAR(average, sigma2, tolerance)
      << "sd of one seed " << sd_one / sigma2 << " of sigma^2 = " << sigma2;
}

TEST(RandomProfileStatistics, WelchEstimateMatchesThePsdInBands) {
  // One seed, 16 km of FRA3 between 1 and 40 m, read through at() on a 1/16 m grid. Welch:
  // 256 m Hann segments with 50 % overlap (K = 124), one-sided per rad/m:
  //   S_hat(W) = dx / (pi sum w_j^2) |sum_j w_j r_j exp(-i W x_j)|^2,
  // which integrates to the mean square (a tone A cos(W0 x) gives A^2/2). Averaged over the m
  // DFT lines of a band of +-10 % around a centre wavelength, compared with the PSD averaged
  // over the same lines. Degrees of freedom: 2 per line and segment, halved for the overlap and
  // halved again for the correlation of neighbouring Hann lines: nu = K m / 2; the relative
  // standard deviation of the estimate is sqrt(2 / nu); tolerance 4 of them.
  const double lmin = 1.0, lmax = 40.0, x0 = 0.0, x1 = 16000.0, dx = 1.0 / 16.0;
  const RoughnessSpectrum psd = RoughnessSpectrum::fra(3);
  const Unevenness u(spec("FRA3", 2024, lmin, lmax), {0.46}, x0, x1);
  const int seg = 4096;  // samples per segment: 256 m
  const auto total = static_cast<int>((x1 - x0) / dx);
  std::vector<double> r(static_cast<std::size_t>(total));
  for (int j = 0; j < total; ++j) r[static_cast<std::size_t>(j)] = u.at(0, x0 + j * dx, 0.0);
  std::vector<double> window(seg);
  double window_power = 0.0;
  for (int j = 0; j < seg; ++j) {
    window[static_cast<std::size_t>(j)] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * j / seg));
    window_power += window[static_cast<std::size_t>(j)] * window[static_cast<std::size_t>(j)];
  }
  const double line = 2.0 * std::numbers::pi / (seg * dx);  // DFT line spacing [rad/m]
  std::vector<std::complex<double>> twiddle(seg);           // exp(-2 pi i n / seg)
  for (int n = 0; n < seg; ++n)
    twiddle[static_cast<std::size_t>(n)] = std::polar(1.0, -2.0 * std::numbers::pi * n / seg);

  for (double centre : {2.0, 5.0, 10.0, 20.0}) {  // m, inside the band, away from its edges
    SCOPED_TRACE(centre);
    const double w_c = 2.0 * std::numbers::pi / centre;
    const int k_first = static_cast<int>(std::ceil(0.9 * w_c / line));
    const int k_last = static_cast<int>(std::floor(1.1 * w_c / line));
    const int m = k_last - k_first + 1;
    double estimate = 0.0, truth = 0.0;
    int segments = 0;
    for (int start = 0; start + seg <= total; start += seg / 2, ++segments) {
      for (int k = k_first; k <= k_last; ++k) {
        std::complex<double> sum = 0.0;
        for (int j = 0; j < seg; ++j) {
          sum += window[static_cast<std::size_t>(j)] * r[static_cast<std::size_t>(start + j)] *
                 twiddle[static_cast<std::size_t>((j * k) % seg)];
        }
        estimate += dx / (std::numbers::pi * window_power) * std::norm(sum);
      }
    }
    for (int k = k_first; k <= k_last; ++k) truth += psd(k * line);
    estimate /= static_cast<double>(segments) * m;
    truth /= m;
    const double nu = segments * m / 2.0;
    const double tolerance = 4.0 * std::sqrt(2.0 / nu);
    ASSERT_LT(tolerance, 0.5);  // a factor 2 or 2 pi error stays visible
    EXPECT_NEAR(estimate / truth, 1.0, tolerance) << m << " lines, " << segments << " segments";
  }
}

}  // namespace
}  // namespace rumble
