#include "output/probe_locator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rumble::fem {

ProbeCandidate best_tetrahedron(const TetMesh& mesh, const Eigen::Vector3d& p) {
  // The tetrahedron whose smallest barycentric coordinate is largest: the containing one, or on
  // a face shared by two, either gives the same interpolation.
  ProbeCandidate best;
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const Tetrahedron& t = mesh.tets[e];
    const Eigen::Vector3d x0 = mesh.node(t[0]);
    // Cheap rejection: outside the bounding box.
    Eigen::Vector3d lo = x0, hi = x0;
    for (int a = 1; a < 4; ++a) {
      lo = lo.cwiseMin(mesh.node(t[a]));
      hi = hi.cwiseMax(mesh.node(t[a]));
    }
    const double slack = 1e-6 * (hi - lo).maxCoeff();
    if (((p - lo).array() < -slack).any() || ((p - hi).array() > slack).any()) continue;
    Eigen::Matrix3d J;
    J << mesh.node(t[1]) - x0, mesh.node(t[2]) - x0, mesh.node(t[3]) - x0;
    const Eigen::Vector3d xi = J.partialPivLu().solve(p - x0);
    const std::array<double, 4> w{1.0 - xi.sum(), xi[0], xi[1], xi[2]};
    const double smallest = *std::min_element(w.begin(), w.end());
    if (smallest > best.smallest) best = {{t, w}, smallest, static_cast<std::int64_t>(e)};
  }
  return best;
}

void refuse_probe_outside(const std::string& name, double x, double y, double depth) {
  std::ostringstream m;
  m << "fem: receiver '" << name << "' at x " << x << " m, y " << y << " m, depth " << depth
    << " m lies outside the mesh; move it or enlarge params/mesh/radius";
  throw std::invalid_argument(m.str());
}

ProbePoint locate_probe(const TetMesh& mesh, double x, double y, double depth,
                        const std::string& name) {
  const ProbeCandidate best = best_tetrahedron(mesh, Eigen::Vector3d(x, y, depth));
  if (!best.inside()) refuse_probe_outside(name, x, y, depth);
  return best.point;
}

}  // namespace rumble::fem
