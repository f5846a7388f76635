#include "post/peak_frequency.hpp"

#include <cmath>
#include <limits>
#include <optional>

namespace rumble::post {
namespace {

/// The time [samples from 0] where v first changes sign from the peak's walking from `peak` by
/// `step` (+1 or -1); nothing when it reaches the record's end first.
std::optional<double> crossing(std::span<const double> v, std::size_t peak, long step) {
  const bool positive = v[peak] > 0.0;
  for (long k = static_cast<long>(peak) + step; k >= 0 && k < static_cast<long>(v.size());
       k += step) {
    const double here = v[static_cast<std::size_t>(k)];
    if ((here > 0.0) == positive && here != 0.0) continue;
    const double there = v[static_cast<std::size_t>(k - step)];  // same sign as the peak
    const double fraction = there / (there - here);              // of the step towards k
    return static_cast<double>(k - step) + fraction * static_cast<double>(step);
  }
  return std::nullopt;
}

}  // namespace

double peak_half_cycle_frequency(std::span<const double> v, std::size_t peak, double dt) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (peak >= v.size() || v[peak] == 0.0 || !std::isfinite(v[peak])) return kNaN;
  const std::optional<double> before = crossing(v, peak, -1), after = crossing(v, peak, +1);
  const auto at = static_cast<double>(peak);
  if (before && after) return 1.0 / (2.0 * (*after - *before) * dt);
  if (before) return 1.0 / (4.0 * (at - *before) * dt);
  if (after) return 1.0 / (4.0 * (*after - at) * dt);
  return kNaN;
}

}  // namespace rumble::post
