#include "track/unevenness_random.hpp"

#include <algorithm>
#include <bit>
#include <complex>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/number_text.hpp"

namespace rumble {
namespace {

/// In place a_j <- sum_k a_k exp(+2 pi i j k / n), n a power of two (iterative radix-2
/// Cooley-Tukey; twiddles from a table of exact cos/sin, so the error stays O(eps log n)).
void synthesize(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {  // bit-reversal permutation
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  std::vector<std::complex<double>> w(n / 2);
  for (std::size_t k = 0; k < n / 2; ++k) {
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    w[k] = {std::cos(angle), std::sin(angle)};
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const std::size_t half = len / 2, stride = n / len;
    for (std::size_t i = 0; i < n; i += len) {
      for (std::size_t k = 0; k < half; ++k) {
        const std::complex<double> u = a[i + k], v = a[i + k + half] * w[k * stride];
        a[i + k] = u + v;
        a[i + k + half] = u - v;
      }
    }
  }
}

}  // namespace

RandomProfile::RandomProfile(const RoughnessSpectrum& spectrum, double wavelength_min,
                             double wavelength_max, std::uint64_t seed, double x_min,
                             double x_max) {
  if (!(wavelength_min > 0.0) || !(wavelength_max > wavelength_min) ||
      !std::isfinite(wavelength_max)) {
    throw std::invalid_argument("random profile: need 0 < wavelength_min < wavelength_max, got " +
                                number_text(wavelength_min) + " m and " +
                                number_text(wavelength_max) + " m");
  }
  if (!spectrum.above_min(wavelength_min) || !spectrum.below_max(wavelength_max)) {
    throw std::invalid_argument(
        "random profile: the " + spectrum.name() + " spectrum is defined for wavelengths from " +
        number_text(spectrum.min_wavelength()) + " m to " + number_text(spectrum.max_wavelength()) +
        " m, got " + number_text(wavelength_min) + " m to " + number_text(wavelength_max) + " m");
  }
  if (!(x_max > x_min) || !std::isfinite(x_max - x_min)) {
    throw std::invalid_argument("random profile: the track span [" + number_text(x_min) + ", " +
                                number_text(x_max) + "] m is empty");
  }
  dx_ = wavelength_min / kPointsPerMinWavelength;
  const double needed = std::max(x_max - x_min, kMinPeriodsOfMaxWavelength * wavelength_max);
  const double cells = std::ceil(needed / dx_);
  if (!(cells <= static_cast<double>(kMaxSamples))) {
    throw std::invalid_argument(
        "random profile: " + number_text(needed) + " m at a spacing of wavelength_min/" +
        std::to_string(kPointsPerMinWavelength) + " = " + number_text(dx_) + " m needs " +
        number_text(cells) + " points, more than " + std::to_string(kMaxSamples) +
        "; raise wavelength_min, lower wavelength_max or shorten the track");
  }
  const std::size_t n = std::max<std::size_t>(std::bit_ceil(static_cast<std::size_t>(cells)), 64);
  x0_ = x_min;
  inv_dx_ = 1.0 / dx_;
  n_ = static_cast<double>(n);
  line_spacing_ = 2.0 * std::numbers::pi / (n_ * dx_);

  // Line k stands for the bin [(k - 1/2), (k + 1/2)) dOmega; its power is the PSD's integral
  // over the part of the bin inside the band, so the lines' powers add up to the band's
  // integral exactly. The highest line is far below the grid's Nyquist line n/2 (16 points
  // per shortest wavelength: k_last ~ n/16).
  const double w_lo = 2.0 * std::numbers::pi / wavelength_max,
               w_hi = 2.0 * std::numbers::pi / wavelength_min;
  const auto k_first =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(w_lo / line_spacing_ + 0.5)));
  const auto k_last = static_cast<std::size_t>(std::floor(w_hi / line_spacing_ + 0.5));
  std::vector<std::complex<double>> lines(n);
  std::mt19937_64 rng(seed);
  for (std::size_t k = k_first; k <= k_last; ++k) {
    const double kd = static_cast<double>(k);
    const double lo = std::max(w_lo, (kd - 0.5) * line_spacing_);
    const double hi = std::min(w_hi, (kd + 0.5) * line_spacing_);
    const double power = hi > lo ? spectrum.integral(lo, hi) : 0.0;  // m^2
    const double phase = 2.0 * std::numbers::pi * static_cast<double>(rng() >> 11) * 0x1p-53;
    lines[k] = std::polar(std::sqrt(2.0 * power), phase);
    mean_square_ += power;
  }
  synthesize(lines);  // samples_j = Re sum_k A_k exp(i phi_k) exp(2 pi i j k / n)
  samples_.resize(n + 1);
  for (std::size_t j = 0; j < n; ++j) samples_[j] = lines[j].real();
  samples_[n] = samples_[0];
}

}  // namespace rumble
