// The rectangle on the ground that the footprints cover, and the distance from it: what the
// mesh grading and the boundary springs measure distances from. Frame of tet_mesh.hpp [m].
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <rumble/plugin.hpp>
#include <vector>

namespace rumble::fem {

struct TrackRegion {
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;  // [m] extent of every footprint

  static TrackRegion of(const std::vector<Footprint>& footprints) {
    TrackRegion r{std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
    for (const Footprint& f : footprints) {
      r.x0 = std::min(r.x0, f.x - 0.5 * f.width);
      r.x1 = std::max(r.x1, f.x + 0.5 * f.width);
      r.y0 = std::min(r.y0, f.y - 0.5 * f.length);
      r.y1 = std::max(r.y1, f.y + 0.5 * f.length);
    }
    return r;
  }
  double centre_x() const { return 0.5 * (x0 + x1); }
  double centre_y() const { return 0.5 * (y0 + y1); }
  /// Distance [m] from (x, y, depth) to the rectangle.
  double distance(double x, double y, double depth) const {
    const double dx = std::max({x0 - x, 0.0, x - x1}), dy = std::max({y0 - y, 0.0, y - y1});
    return std::sqrt(dx * dx + dy * dy + depth * depth);
  }
  /// Half the diagonal [m]: the hemisphere must be larger than this.
  double half_diagonal() const { return 0.5 * std::hypot(x1 - x0, y1 - y0); }
};

}  // namespace rumble::fem
