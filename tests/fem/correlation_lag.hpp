// The delay between two traces sampled alike, for the wave-speed checks of the FEM soil tests.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rumble::test {

/// The lag [s] maximizing the cross-correlation of b against a (same sample times, spacing dt),
/// refined by a parabola through the best three lags.
inline double correlation_lag(const std::vector<double>& a, const std::vector<double>& b,
                              double dt) {
  const std::size_t n = a.size();
  std::vector<double> c(n, 0.0);
  for (std::size_t lag = 0; lag < n; ++lag)
    for (std::size_t k = 0; k + lag < n; ++k) c[lag] += a[k] * b[k + lag];
  const std::size_t best = std::max_element(c.begin() + 1, c.end() - 1) - c.begin();
  const double shift =
      0.5 * (c[best - 1] - c[best + 1]) / (c[best - 1] - 2.0 * c[best] + c[best + 1]);
  return (static_cast<double>(best) + shift) * dt;
}

}  // namespace rumble::test
