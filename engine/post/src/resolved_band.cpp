#include "post/resolved_band.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "post/fft.hpp"

namespace rumble::post {

double energy_share_above(const Spectrum& power, double f_hz) {
  double total = 0.0, above = 0.0;
  for (std::size_t k = 0; k < power.values.size(); ++k) {
    total += power.values[k];
    if (power.frequency(k) > f_hz) above += power.values[k];
  }
  return total > 0.0 ? above / total : 0.0;
}

std::vector<double> zero_phase_low_pass(std::span<const double> v, double dt, double f_c) {
  const std::size_t n = fft_friendly_size(2 * v.size());
  ComplexFft forward(n, ComplexFft::Direction::kForward);
  ComplexFft backward(n, ComplexFft::Direction::kBackward);
  std::span<std::complex<double>> in = forward.input();
  std::fill(in.begin(), in.end(), std::complex<double>(0.0));
  std::copy(v.begin(), v.end(), in.begin());
  forward.execute();
  const double df = 1.0 / (static_cast<double>(n) * dt);
  std::span<std::complex<double>> spectrum = backward.input();
  for (std::size_t k = 0; k < n; ++k) {
    const double f = df * static_cast<double>(std::min(k, n - k));  // |f| of bin k
    const double gain = 1.0 / std::sqrt(1.0 + std::pow(f / f_c, 2 * kLowPassOrder));
    spectrum[k] = forward.output()[k] * gain;
  }
  backward.execute();
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out[i] = backward.output()[i].real() / static_cast<double>(n);
  return out;
}

}  // namespace rumble::post
