#include "boundary/absorbing_boundary.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "boundary/static_far_field.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

namespace {

/// The spring per unit area [N/m^3] that holds the half-space's static field of `loads` at x
/// (outward normal n): with u the field's displacement and f = -sigma n the traction the
/// spring must give, S = f f^T / (u . f) + across (I - u u^T / |u|^2), symmetric, S u = f, and
/// positive definite when u . f > 0 (docs/fem-soil.md section 3.2). Zero when the field is
/// too far from that (u . f below a tenth of |u| |f|): the caller falls back to Liu's.
Eigen::Matrix3d half_space_spring(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                  const std::vector<LoadPoint>& loads, double G, double nu,
                                  double across) {
  const HeldField held = half_space_field(x, n, loads, G, nu);
  const Eigen::Vector3d &u = held.displacement, &f = held.spring_force;
  const double work = u.dot(f);
  if (!u.allFinite() || !f.allFinite() || !(work > 0.1 * u.norm() * f.norm()))
    return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d unit = u.normalized();
  return f * f.transpose() / work +
         across * (Eigen::Matrix3d::Identity() - unit * unit.transpose());
}

/// Liu et al.'s spring per unit area [N/m^3]: alpha_N G / r along n, alpha_T G / r across.
Eigen::Matrix3d liu_spring(const Eigen::Vector3d& n, const BoundaryRequest& b, double G_over_r) {
  const double along = b.alpha_normal * G_over_r, across = b.alpha_tangential * G_over_r;
  return across * Eigen::Matrix3d::Identity() + (along - across) * n * n.transpose();
}

}  // namespace

SurfaceShares truncation_shares(const TetMesh& mesh, const TrackRegion& region) {
  std::vector<std::int32_t> index(mesh.node_count(), -1);
  SurfaceShares shares;
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
        index[v] = static_cast<std::int32_t>(shares.nodes.size());
        shares.nodes.push_back(v);
        shares.area.push_back(0.0);
        shares.weighted_normal.emplace_back(Eigen::Vector3d::Zero());
      }
      shares.area[index[v]] += area / 3.0;
      shares.weighted_normal[index[v]] += area * n;
    }
  }
  return shares;
}

std::vector<BoundaryNode> fitted_boundary(const TetMesh& mesh, const FemSettings& settings,
                                          const std::vector<Footprint>& footprints,
                                          const SurfaceShares& shares) {
  const TrackRegion region = TrackRegion::of(footprints);
  // The springs are fitted to a uniform pressure on every footprint.
  double total_area = 0.0;
  for (const Footprint& f : footprints) total_area += f.length * f.width;
  std::vector<LoadPoint> loads;
  for (const Footprint& f : footprints)  // (a region that is a point: the footprint takes all)
    add_load_points(f, total_area > 0.0 ? f.length * f.width / total_area : 1.0, loads);
  const bool half_space = settings.boundary.spring_model == SpringModel::kHalfSpace;
  const double floor_distance = 1e-3 * settings.mesh.radius;
  std::vector<BoundaryNode> nodes(shares.nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    BoundaryNode& b = nodes[k];
    b.node = shares.nodes[k];
    b.area = shares.area[k];
    b.normal = shares.weighted_normal[k].normalized();
    const Eigen::Vector3d x = mesh.node(b.node);
    const soils::SoilProperties& p = settings.properties_at(std::max(x[2], 0.0));
    const soils::WaveSpeeds c = soils::wave_speeds(p.E, p.nu, p.rho);
    b.dashpot_normal = p.rho * c.pressure * b.area;
    b.dashpot_tangential = p.rho * c.shear * b.area;
    const double G = p.shear_modulus();
    const double G_over_r = G / std::max(region.distance(x[0], x[1], x[2]), floor_distance);
    Eigen::Matrix3d spring = Eigen::Matrix3d::Zero();
    if (half_space)
      spring = half_space_spring(x, b.normal, loads, G, p.nu,
                                 settings.boundary.alpha_tangential * G_over_r);
    if (spring.isZero(0.0)) spring = liu_spring(b.normal, settings.boundary, G_over_r);
    b.spring = b.area * spring;
  }
  return nodes;
}

std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const std::vector<Footprint>& footprints) {
  return fitted_boundary(mesh, settings, footprints,
                         truncation_shares(mesh, TrackRegion::of(footprints)));
}

std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const TrackRegion& region) {
  const Footprint spread{region.centre_x(), region.centre_y(), region.y1 - region.y0,
                         region.x1 - region.x0};
  return absorbing_boundary(mesh, settings, std::vector<Footprint>{spread});
}

std::vector<char> held_nodes(Eigen::Index nodes, const std::vector<BoundaryNode>& boundary,
                             const FemSettings& settings) {
  std::vector<char> held(static_cast<std::size_t>(nodes), 0);
  if (settings.boundary.kind == BoundaryKind::kFixed ||
      settings.boundary.kind == BoundaryKind::kPml)
    for (const BoundaryNode& b : boundary) held[static_cast<std::size_t>(b.node)] = 1;
  return held;
}

}  // namespace rumble::fem
