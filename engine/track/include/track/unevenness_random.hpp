// A random rail profile r(x) [m] with a given one-sided PSD, synthesized once by the spectral
// representation method (sum of cosines with independent uniform random phases; Rice 1944,
// Shinozuka & Deodatis, Appl. Mech. Rev. 44(4), 1991):
//     r(x) = sum_k A_k cos(k dOmega s + phi_k),   s = x - x_min,   dOmega = 2 pi / P,
//     A_k^2 / 2 = integral of S over [(k - 1/2) dOmega, (k + 1/2) dOmega] clipped to the band
//                 [2 pi / wavelength_max, 2 pi / wavelength_min],
// so that the mean square of r over one period P is exactly the integral of S over the band
// (the PSD is per rad/m; see unevenness_psd.hpp). phi_k = 2 pi u_k with u_k the top 53 bits of
// successive std::mt19937_64(seed) outputs, k ascending: the same seed gives the same profile
// on every platform (std::uniform_real_distribution is not portable, the engine is).
//
// The sum is evaluated once on a uniform grid by one FFT and read back by linear
// interpolation: O(1), allocation-free per call. Grid choices (all derived, none configurable):
//   spacing   dx = wavelength_min / 16: linear interpolation keeps (2 + cos(2 pi/16))/3 = 97.5 %
//             of the mean square of the shortest wave, more of longer ones (the grid values
//             themselves are exact);
//   period    P = N dx with N the smallest power of two such that P >= the span x_max - x_min
//             (no repetition along the track) and P >= 32 wavelength_max (line spacing at most
//             1/32 of the lowest band frequency, so the band is resolved by >= 31 lines);
//   size      N <= 2^22 (32 MiB of samples); a longer track or finer band is refused.
// Outside [x_min, x_min + P) the profile repeats with period P.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "track_spec/unevenness_psd.hpp"

namespace rumble {

class RandomProfile {
 public:
  static constexpr int kPointsPerMinWavelength = 16;
  static constexpr int kMinPeriodsOfMaxWavelength = 32;
  static constexpr std::size_t kMaxSamples = std::size_t{1} << 22;

  /// Throws std::invalid_argument when the band is empty or outside the spectrum's range, the
  /// span is empty, or the grid would exceed kMaxSamples.
  RandomProfile(const RoughnessSpectrum& spectrum, double wavelength_min, double wavelength_max,
                std::uint64_t seed, double x_min, double x_max);

  /// r(x) [m], linear between grid points, periodic with period().
  double at(double x) const noexcept {
    double s = (x - x0_) * inv_dx_;
    s -= n_ * std::floor(s / n_);  // wrap into [0, N]
    auto i = static_cast<std::size_t>(s);
    if (i >= samples_.size() - 1) i = samples_.size() - 2;  // s == N after rounding
    const double f = s - static_cast<double>(i);
    return samples_[i] + f * (samples_[i + 1] - samples_[i]);
  }

  double spacing() const { return dx_; }                    // dx [m]
  double period() const { return dx_ * n_; }                // P [m]
  double line_spacing() const { return line_spacing_; }     // dOmega [rad/m]
  double mean_square() const { return mean_square_; }       // sum A_k^2/2 [m^2]
  std::size_t size() const { return samples_.size() - 1; }  // N
  /// Grid values r(x_min + j dx), j = 0 .. N - 1 [m].
  double sample(std::size_t j) const { return samples_[j]; }

 private:
  double x0_ = 0.0, dx_ = 1.0, inv_dx_ = 1.0, n_ = 1.0;
  double line_spacing_ = 0.0, mean_square_ = 0.0;
  std::vector<double> samples_;  // N + 1 values, the last equal to the first (wrap-around)
};

}  // namespace rumble
