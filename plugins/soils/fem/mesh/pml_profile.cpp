#include "mesh/pml_profile.hpp"

#include <algorithm>
#include <cmath>

namespace rumble::fem {

Eigen::Vector3d PmlProfile::depth_into(const Eigen::Vector3d& p) const {
  Eigen::Vector3d d;
  for (int i = 0; i < 2; ++i) d[i] = std::max({low[i] - p[i], 0.0, p[i] - high[i]});
  d[2] = std::max(0.0, p[2] - high[2]);  // the ground (depth 0) is free: no layer above
  return d;
}

Eigen::Vector3d PmlProfile::damping_at(const Eigen::Vector3d& p, double c_p) const {
  // Order-2 profile: the continuum reflection at normal incidence is
  // exp(-2 / c_p integral_0^L d) = exp(-2 d0 L / (3 c_p)) = R.
  const double d0 = 3.0 * c_p * std::log(1.0 / reflection) / (2.0 * thickness);
  const Eigen::Vector3d x = depth_into(p) / thickness;
  return d0 * x.cwiseProduct(x);
}

}  // namespace rumble::fem
