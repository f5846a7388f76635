#include "frequency/resolved_band.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rumble::fem {
namespace {

/// Mean edge length of a tetrahedron [m].
double mean_edge(const TetMesh& mesh, const Tetrahedron& t) {
  double sum = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) sum += (mesh.node(t[a]) - mesh.node(t[b])).norm();
  return sum / 6.0;
}

/// The straight path from the footprints' nearest surface point to p.
struct Path {
  Eigen::Vector3d from, to;
  Eigen::Vector3d at(int k) const {
    return from + (to - from) * (static_cast<double>(k) / (kPathSamples - 1));
  }
};

Path path_to(const TrackRegion& r, const Eigen::Vector3d& p) {
  const Eigen::Vector3d nearest(std::clamp(p.x(), r.x0, r.x1), std::clamp(p.y(), r.y0, r.y1), 0.0);
  return {nearest, p};
}

/// Whether the barycentric coordinates of q in t are all above -tolerance.
bool contains(const TetMesh& mesh, const Tetrahedron& t, const Eigen::Vector3d& q) {
  const Eigen::Vector3d x0 = mesh.node(t[0]);
  Eigen::Matrix3d J;
  J << mesh.node(t[1]) - x0, mesh.node(t[2]) - x0, mesh.node(t[3]) - x0;
  const Eigen::Vector3d xi = J.partialPivLu().solve(q - x0);
  return std::min({1.0 - xi.sum(), xi[0], xi[1], xi[2]}) >= -1e-9;
}

}  // namespace

std::vector<double> path_resolved_frequency(const TetMesh& mesh, const TrackRegion& region,
                                            const std::vector<Eigen::Vector3d>& points, double c_r,
                                            double n) {
  std::vector<Path> paths;
  for (const Eigen::Vector3d& p : points) paths.push_back(path_to(region, p));
  // h[p][k]: the largest tetrahedron holding sample k of path p (0: none found yet).
  std::vector<std::array<double, kPathSamples>> h(paths.size());
  for (auto& row : h) row.fill(0.0);
  for (const Tetrahedron& t : mesh.tets) {
    Eigen::Vector3d lo = mesh.node(t[0]), hi = lo;
    for (int a = 1; a < 4; ++a) {
      lo = lo.cwiseMin(mesh.node(t[a]));
      hi = hi.cwiseMax(mesh.node(t[a]));
    }
    const Eigen::Vector3d slack = Eigen::Vector3d::Constant(1e-9 * (hi - lo).maxCoeff());
    double size = -1.0;  // computed once a sample falls inside
    for (std::size_t p = 0; p < paths.size(); ++p) {
      const Eigen::Vector3d plo = paths[p].from.cwiseMin(paths[p].to) - slack;
      const Eigen::Vector3d phi = paths[p].from.cwiseMax(paths[p].to) + slack;
      if ((phi.array() < lo.array()).any() || (plo.array() > hi.array()).any()) continue;
      for (int k = 0; k < kPathSamples; ++k) {
        const Eigen::Vector3d q = paths[p].at(k);
        if (((q - lo).array() < -slack.array()).any() || ((q - hi).array() > slack.array()).any() ||
            !contains(mesh, t, q))
          continue;
        if (size < 0.0) size = mean_edge(mesh, t);
        h[p][static_cast<std::size_t>(k)] = std::max(h[p][static_cast<std::size_t>(k)], size);
      }
    }
  }
  std::vector<double> f(paths.size(), 0.0);
  for (std::size_t p = 0; p < paths.size(); ++p) {
    const double largest = *std::max_element(h[p].begin(), h[p].end());
    if (largest > 0.0) f[p] = c_r / (n * largest);
  }
  return f;
}

}  // namespace rumble::fem
