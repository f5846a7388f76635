// The truncation surface's per-node impedance: Lysmer-Kuhlemeyer dashpots rho c_p along the
// normal and rho c_s along the tangents [N s/m^3], and springs alpha_N G / r and alpha_T G / r
// [N/m^3] (viscous-spring boundary, Liu et al. 2006; r the distance from the footprints), each
// times the node's share of the surface (a third of every adjacent triangle). The normal is the
// area-weighted mean of the adjacent faces' (numerics.md §2.4). Each node gets two 3 x 3 blocks
//   D = d_t I + (d_n - d_t) n n^T,   S = s_t I + (s_n - s_t) n n^T,
// lumped on the node: no extra unknowns, the explicit step stays explicit.
#pragma once

#include <Eigen/Core>
#include <cstdint>
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
  double spring_normal = 0.0, spring_tangential = 0.0;    // N/m

  /// y += B x for the block B = t I + (n - t) nn^T.
  static void apply(const Eigen::Vector3d& normal, double along_normal, double tangential,
                    const double* x, double* y) {
    const double xn = normal[0] * x[0] + normal[1] * x[1] + normal[2] * x[2];
    for (int c = 0; c < 3; ++c)
      y[c] += tangential * x[c] + (along_normal - tangential) * xn * normal[c];
  }
};

/// Every node of the truncation surface, with its blocks for the settings' boundary kind (for a
/// fixed boundary only node and area are meaningful).
std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const TrackRegion& region);

}  // namespace rumble::fem
