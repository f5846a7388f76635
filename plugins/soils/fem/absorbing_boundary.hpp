// The truncation surface's per-node impedance: Lysmer-Kuhlemeyer dashpots rho c_p along the
// normal and rho c_s along the tangents [N s/m^3], and a symmetric 3 x 3 spring [N/m^3] that
// gives the static support (docs/fem-soil.md section 3): by default fitted so that the
// half-space's static field of the footprints' load holds exactly (section 3.2), or Liu et
// al.'s (2006) alpha_N G / r along the normal and alpha_T G / r along the tangents (r the
// distance from the footprints). Each times the node's share of the surface (a third of every
// adjacent triangle); the normal is the area-weighted mean of the adjacent faces'. Lumped on
// the node: no extra unknowns, the explicit step stays explicit.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <vector>

#include "fem_settings.hpp"
#include "tet_mesh.hpp"
#include "track_region.hpp"

namespace rumble::fem {

struct BoundaryNode {
  std::int32_t node = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      // outward unit normal
  double area = 0.0;                                      // m^2
  double dashpot_normal = 0.0, dashpot_tangential = 0.0;  // N s/m
  Eigen::Matrix3d spring = Eigen::Matrix3d::Zero();       // N/m, symmetric positive definite

  /// y += B x for the block B = t I + (n - t) nn^T.
  static void apply(const Eigen::Vector3d& normal, double along_normal, double tangential,
                    const double* x, double* y) {
    const double xn = normal[0] * x[0] + normal[1] * x[1] + normal[2] * x[2];
    for (int c = 0; c < 3; ++c)
      y[c] += tangential * x[c] + (along_normal - tangential) * xn * normal[c];
  }
  /// y += scale D x, D the dashpots' block.
  void apply_dashpot(const double* x, double* y, double scale = 1.0) const {
    apply(normal, scale * dashpot_normal, scale * dashpot_tangential, x, y);
  }
  /// y += S x, S the spring.
  void apply_spring(const double* x, double* y) const {
    for (int r = 0; r < 3; ++r)
      y[r] += spring(r, 0) * x[0] + spring(r, 1) * x[1] + spring(r, 2) * x[2];
  }
};

/// Every node of the truncation surface, with its blocks for the settings' boundary kind (for a
/// fixed boundary only node and area are meaningful). The half-space springs are fitted to a
/// uniform pressure on the footprints; distances are measured from their rectangle.
std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const std::vector<Footprint>& footprints);
/// The same with one load spread over the region's rectangle (a point when it has no area).
std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const TrackRegion& region);

}  // namespace rumble::fem
