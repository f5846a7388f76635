#include "post/spectrum.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rumble::post {

SpectrumAnalyzer::SpectrumAnalyzer(std::size_t n, Window window) : fft_(n), window_(n, 1.0) {
  if (window == Window::kHann) {
    for (std::size_t i = 0; i < n; ++i)
      window_[i] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * static_cast<double>(i) /
                                         static_cast<double>(n)));
  }
  for (double w : window_) {
    sum_w_ += w;
    sum_w2_ += w * w;
  }
}

Spectrum SpectrumAnalyzer::one_sided(std::span<const double> x, double dt, int power,
                                     double divisor) {
  if (x.size() != fft_.size())
    throw std::invalid_argument("SpectrumAnalyzer: a record of " + std::to_string(x.size()) +
                                " samples given to an analyzer made for " +
                                std::to_string(fft_.size()));
  if (!(dt > 0.0))
    throw std::invalid_argument("SpectrumAnalyzer: time step " + std::to_string(dt) +
                                " s is not > 0");
  std::span<double> in = fft_.input();
  for (std::size_t i = 0; i < x.size(); ++i) in[i] = window_[i] * x[i];
  fft_.execute();
  const std::size_t n = fft_.size();
  Spectrum s;
  s.df = 1.0 / (static_cast<double>(n) * dt);
  const auto out = fft_.output();
  s.values.resize(out.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const bool single = k == 0 || 2 * k == n;
    const double magnitude = power == 1 ? std::abs(out[k]) : std::norm(out[k]);
    s.values[k] = (single ? 1.0 : 2.0) * magnitude / divisor;
  }
  return s;
}

Spectrum SpectrumAnalyzer::amplitude(std::span<const double> x, double dt) {
  return one_sided(x, dt, 1, sum_w_);
}

Spectrum SpectrumAnalyzer::power(std::span<const double> x, double dt) {
  return one_sided(x, dt, 2, static_cast<double>(fft_.size()) * sum_w2_);
}

double dominant_frequency(const Spectrum& amplitude, double f_min) {
  const std::vector<double>& a = amplitude.values;
  std::size_t best = a.size();
  for (std::size_t k = 1; k < a.size(); ++k) {
    if (amplitude.frequency(k) < f_min) continue;
    if (best == a.size() ? a[k] > 0.0 : a[k] > a[best]) best = k;
  }
  if (best == a.size()) return std::numeric_limits<double>::quiet_NaN();
  double shift = 0.0;  // bins, from the parabola through the peak and its neighbours
  if (best > 0 && best + 1 < a.size()) {
    if (a[best - 1] > 0.0 && a[best + 1] > 0.0) {  // through the logarithms: a Gaussian fit
      const double l = std::log(a[best - 1]), c = std::log(a[best]), r = std::log(a[best + 1]);
      const double denom = l - 2.0 * c + r;
      if (denom < 0.0) shift = 0.5 * (l - r) / denom;
    }
  }
  return (static_cast<double>(best) + shift) * amplitude.df;
}

}  // namespace rumble::post
