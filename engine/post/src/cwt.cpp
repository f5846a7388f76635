#include "post/cwt.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/number_text.hpp"

namespace rumble::post {
namespace {

constexpr double kPadEnvelopes = 6.0;  // zero padding, in units of the largest scale

double eta_f(double omega0) {
  return 0.5 * (omega0 + std::sqrt(2.0 + omega0 * omega0));
}

void check_options(std::size_t n, double dt, const CwtOptions& o) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("CWT: " + m); };
  if (n < 2) fail("the record has " + std::to_string(n) + " sample(s); at least 2 are needed");
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("time step " + number_text(dt) + " s is not > 0");
  if (!(o.omega0 > 0.0)) fail("omega0 = " + number_text(o.omega0) + " is not > 0 (6 is usual)");
  if (!(o.f_min > 0.0)) fail("f_min = " + number_text(o.f_min) + " Hz is not > 0");
  if (!(o.f_max >= o.f_min))
    fail("f_max = " + number_text(o.f_max) + " Hz is below f_min = " + number_text(o.f_min) +
         " Hz");
  const double nyquist = 0.5 / dt;
  if (!(o.f_max < nyquist))
    fail("f_max = " + number_text(o.f_max) + " Hz is not below the Nyquist frequency " +
         number_text(nyquist) + " Hz of the record (dt = " + number_text(dt) + " s); lower f_max");
  // Before the padding is converted to a size: a step of 1e-300 s asked for 1e300 samples, an
  // undefined conversion (UBSan, found by the post fuzz target, docs/fuzzing.md).
  if (!(cwt_padding(dt, o) <= kMaxCwtPadding))
    fail("f_min = " + number_text(o.f_min) + " Hz at dt = " + number_text(dt) +
         " s needs a zero padding of " + number_text(cwt_padding(dt, o)) +
         " samples (6 wavelet scales), more than " + number_text(kMaxCwtPadding) + "; raise f_min");
  if (o.n_freq == 0) fail("n_freq is 0; at least 1 frequency is needed");
  if (o.time_stride == 0) fail("time_stride is 0; 1 keeps every sample");
}

}  // namespace

double morlet_frequency(double scale, double omega0) {
  return eta_f(omega0) / (2.0 * std::numbers::pi * scale);
}

double morlet_scale(double frequency, double omega0) {
  return eta_f(omega0) / (2.0 * std::numbers::pi * frequency);
}

std::vector<double> log_spaced(double lo, double hi, std::size_t n) {
  std::vector<double> out(n);
  if (n == 1) {
    out[0] = lo;
    return out;
  }
  const double step = std::log(hi / lo) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) out[i] = lo * std::exp(step * static_cast<double>(i));
  out[n - 1] = hi;  // exactly, whatever the rounding of exp
  return out;
}

double cwt_padding(double dt, const CwtOptions& options) {
  return std::ceil(kPadEnvelopes * morlet_scale(options.f_min, options.omega0) / dt);
}

MorletCwt::MorletCwt(std::size_t n, double dt, const CwtOptions& options)
    : n_(n),
      dt_(dt),
      options_((check_options(n, dt, options), options)),
      frequency_(log_spaced(options.f_min, options.f_max, options.n_freq)),
      forward_(fft_friendly_size(n + static_cast<std::size_t>(cwt_padding(dt, options))),
               ComplexFft::Direction::kForward),
      inverse_(forward_.size(), ComplexFft::Direction::kBackward) {
  const double omega0 = options_.omega0;
  const double norm = 2.0 * std::exp(0.5 * std::pow(eta_f(omega0) - omega0, 2));
  const std::size_t len = forward_.size();
  const double domega = 2.0 * std::numbers::pi / (static_cast<double>(len) * dt_);
  scale_.resize(frequency_.size());
  kernel_.resize(frequency_.size());
  for (std::size_t i = 0; i < frequency_.size(); ++i) {
    scale_[i] = morlet_scale(frequency_[i], omega0);
    std::vector<double>& psi = kernel_[i];
    psi.assign(len / 2 + 1, 0.0);  // omega_k = k domega > 0 for k = 1 .. L/2; negative ones: 0
    for (std::size_t k = 1; k < psi.size(); ++k) {
      const double x = scale_[i] * domega * static_cast<double>(k) - omega0;
      psi[k] = norm * std::exp(-0.5 * x * x);
    }
  }
}

Scalogram MorletCwt::transform(const TimeSeries& x) {
  if (x.size() != n_)
    throw std::invalid_argument("CWT: a record of " + std::to_string(x.size()) +
                                " samples given to a transform made for " + std::to_string(n_));
  const std::size_t len = forward_.size();
  std::span<std::complex<double>> in = forward_.input();
  for (std::size_t k = 0; k < len; ++k) in[k] = k < n_ ? x.values[k] : 0.0;
  forward_.execute();
  const auto spectrum = forward_.output();

  Scalogram out;
  out.frequency = frequency_;
  out.scale = scale_;
  const std::size_t stride = options_.time_stride;
  for (std::size_t k = 0; k < n_; k += stride) out.time.push_back(x.time(k));
  const std::size_t n_time = out.time.size();
  out.coi_frequency.resize(n_time);
  const double nyquist = 0.5 / dt_;
  for (std::size_t j = 0; j < n_time; ++j) {
    const std::size_t k = j * stride;
    const double d = static_cast<double>(std::min(k, n_ - 1 - k)) * dt_;  // s, to nearest edge
    const double f = d > 0.0 ? morlet_frequency(d / std::numbers::sqrt2, options_.omega0) : nyquist;
    out.coi_frequency[j] = std::min(f, nyquist);
  }
  out.magnitude.resize(frequency_.size() * n_time);
  std::span<std::complex<double>> back = inverse_.input();
  const double inv_len = 1.0 / static_cast<double>(len);  // FFTW's backward is unnormalised
  for (std::size_t i = 0; i < frequency_.size(); ++i) {
    const std::vector<double>& psi = kernel_[i];
    for (std::size_t k = 0; k < len; ++k) back[k] = k < psi.size() ? spectrum[k] * psi[k] : 0.0;
    inverse_.execute();
    const auto w = inverse_.output();
    for (std::size_t j = 0; j < n_time; ++j)
      out.magnitude[i * n_time + j] = std::abs(w[j * stride]) * inv_len;
  }
  return out;
}

Scalogram cwt_morlet(const TimeSeries& x, const CwtOptions& options) {
  MorletCwt cwt(x.size(), x.dt, options);
  return cwt.transform(x);
}

}  // namespace rumble::post
