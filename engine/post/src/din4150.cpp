#include "post/din4150.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rumble::post {
namespace {

void check_grid(const TimeSeries& x, const char* what) {
  if (!(x.dt > 0.0) || !std::isfinite(x.dt))
    throw std::invalid_argument(std::string(what) + ": time step " + std::to_string(x.dt) +
                                " s is not > 0");
}

}  // namespace

double kb_gain(double f) {
  if (!(f > 0.0)) return 0.0;
  const double r = kKbCornerHz / f;
  return 1.0 / std::sqrt(1.0 + r * r);
}

TimeSeries kb_weight(const TimeSeries& v) {
  check_grid(v, "kb_weight");
  const double w0 = 2.0 * std::numbers::pi * kKbCornerHz;  // rad/s
  const double k = w0 / std::tan(std::numbers::pi * kKbCornerHz * v.dt);
  const double b = k / (k + w0);
  const double a = (w0 - k) / (k + w0);
  TimeSeries y{v.t0, v.dt, std::vector<double>(v.size())};
  double x_prev = 0.0, y_prev = 0.0;  // at rest before the record
  for (std::size_t n = 0; n < v.size(); ++n) {
    y.values[n] = b * (v.values[n] - x_prev) - a * y_prev;
    x_prev = v.values[n];
    y_prev = y.values[n];
  }
  return y;
}

TimeSeries running_rms(const TimeSeries& x, double tau) {
  check_grid(x, "running_rms");
  if (!(tau > 0.0))
    throw std::invalid_argument("running_rms: time constant " + std::to_string(tau) +
                                " s is not > 0 (Fast: 0.125 s, Slow: 1 s)");
  const double a = std::exp(-x.dt / tau);
  const double c = (tau / x.dt) * (1.0 - a);  // weight of the linear part of u over a step
  TimeSeries r{x.t0, x.dt, std::vector<double>(x.size())};
  double q = 0.0, u_prev = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double u = x.values[n] * x.values[n];
    if (n > 0) q = a * q + u - a * u_prev - (u - u_prev) * c;
    u_prev = u;
    r.values[n] = std::sqrt(std::max(q, 0.0));  // q >= 0 exactly; rounding may dip below
  }
  return r;
}

double effective_value(std::span<const double> x) {
  if (x.empty()) return 0.0;
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

KbResult kb_f(const TimeSeries& v, double tau) {
  KbResult out;
  out.kb_f = running_rms(kb_weight(v), tau);
  for (std::size_t n = 0; n < out.kb_f.size(); ++n) {
    const double value = out.kb_f.values[n];
    if (std::isnan(value)) {
      out.kb_f_max = value;
      out.t_max = out.kb_f.time(n);
      break;
    }
    if (value > out.kb_f_max) {
      out.kb_f_max = value;
      out.t_max = out.kb_f.time(n);
    }
  }
  return out;
}

double effective_velocity_max(const TimeSeries& v, double tau) {
  const TimeSeries r = running_rms(v, tau);
  double m = 0.0;
  for (double value : r.values) {
    if (std::isnan(value)) return value;
    m = std::max(m, value);
  }
  return m;
}

}  // namespace rumble::post
