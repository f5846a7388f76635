#include "absorbing_boundary.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "wave_speeds.hpp"

namespace rumble::fem {

std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const TrackRegion& region) {
  std::vector<std::int32_t> index(mesh.node_count(), -1);
  std::vector<BoundaryNode> nodes;
  std::vector<Eigen::Vector3d> weighted_normal;
  // The domain is convex and contains the ground point above the footprints' centre: every
  // outward normal points away from it.
  const Eigen::Vector3d inside(region.centre_x(), region.centre_y(), 0.0);
  for (const Triangle& f : mesh.truncation) {
    Eigen::Vector3d n;
    const double area = triangle_area(mesh, f, &n);
    const Eigen::Vector3d centroid = (mesh.node(f[0]) + mesh.node(f[1]) + mesh.node(f[2])) / 3.0;
    if (n.dot(centroid - inside) < 0.0) n = -n;
    for (std::int32_t v : f) {
      if (index[v] < 0) {
        index[v] = static_cast<std::int32_t>(nodes.size());
        nodes.push_back({.node = v});
        weighted_normal.emplace_back(Eigen::Vector3d::Zero());
      }
      nodes[index[v]].area += area / 3.0;
      weighted_normal[index[v]] += area * n;
    }
  }
  const double floor_distance = 1e-3 * settings.mesh.radius;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    BoundaryNode& b = nodes[k];
    b.normal = weighted_normal[k].normalized();
    const Eigen::Vector3d x = mesh.node(b.node);
    const soils::SoilProperties& p = settings.properties_at(std::max(x[2], 0.0));
    const soils::WaveSpeeds c = soils::wave_speeds(p.E, p.nu, p.rho);
    b.dashpot_normal = p.rho * c.pressure * b.area;
    b.dashpot_tangential = p.rho * c.shear * b.area;
    const double r = std::max(region.distance(x[0], x[1], x[2]), floor_distance);
    const double G_over_r = p.shear_modulus() / r;
    b.spring_normal = settings.boundary.alpha_normal * G_over_r * b.area;
    b.spring_tangential = settings.boundary.alpha_tangential * G_over_r * b.area;
  }
  return nodes;
}

}  // namespace rumble::fem
