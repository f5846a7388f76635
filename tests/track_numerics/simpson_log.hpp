// Composite Simpson rule in u = ln(Omega), for integrals of the roughness spectra (smooth power
// laws there) in the track numerics tests.
#pragma once

#include <cmath>

namespace rumble {

/// The integral of f over [a, b] by composite Simpson in u = ln(Omega), n (even) intervals.
template <class F>
double simpson_log(F&& f, double a, double b, int n = 20000) {
  const double la = std::log(a), h = (std::log(b) - la) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double w = std::exp(la + i * h);
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * f(w) * w;  // dOmega = Omega du
  }
  return sum * h / 3.0;
}

}  // namespace rumble
