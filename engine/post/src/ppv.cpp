#include "post/ppv.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace rumble::post {

Peak peak_abs(std::span<const double> v) {
  Peak p;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const double a = std::abs(v[k]);
    if (std::isnan(a)) return {a, k};  // a diverged record has no meaningful peak
    if (a > p.value) p = {a, k};
  }
  return p;
}

Peak peak_vector(std::span<const double> vx, std::span<const double> vy,
                 std::span<const double> vz) {
  if (vx.size() != vy.size() || vx.size() != vz.size())
    throw std::invalid_argument("peak_vector: components of different lengths (" +
                                std::to_string(vx.size()) + ", " + std::to_string(vy.size()) +
                                ", " + std::to_string(vz.size()) + ")");
  Peak p;
  for (std::size_t k = 0; k < vx.size(); ++k) {
    const double a = std::sqrt(vx[k] * vx[k] + vy[k] * vy[k] + vz[k] * vz[k]);
    if (std::isnan(a)) return {a, k};
    if (a > p.value) p = {a, k};
  }
  return p;
}

std::vector<ReceiverPpv> ppv_versus_distance(std::vector<ReceiverPpv> receivers) {
  std::stable_sort(
      receivers.begin(), receivers.end(), [](const ReceiverPpv& a, const ReceiverPpv& b) {
        return std::tie(a.distance, a.depth, a.name) < std::tie(b.distance, b.depth, b.name);
      });
  return receivers;
}

}  // namespace rumble::post
