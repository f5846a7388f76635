// Where a perfectly matched layer lies (boundary/pml.hpp): the physical box and the layer's
// thickness and damping profile beyond it. Geometry only, so that the mesh plan can lay the layer
// out (mesh_generator.hpp) without the layer's physics.
#pragma once

#include <Eigen/Core>

namespace rumble::fem {

/// The physical box (frame of tet_mesh.hpp: x, y, depth) and the layer beyond it.
struct PmlProfile {
  Eigen::Vector3d low = Eigen::Vector3d::Zero();   // [m] x0, y0, depth 0 (the ground: no layer)
  Eigen::Vector3d high = Eigen::Vector3d::Zero();  // [m] x1, y1, depth of the box's bottom
  double thickness = 0.0;                          // [m]
  double reflection = 1e-3;                        // [-] R of a normally incident P wave
  double shift = 0.0;                              // alpha [1/s], the frequency shift

  /// Distance [m] beyond the physical box along each axis at p (0 inside it; none above ground).
  Eigen::Vector3d depth_into(const Eigen::Vector3d& p) const;
  /// d_i [1/s] at p for a medium of P-wave speed c_p [m/s].
  Eigen::Vector3d damping_at(const Eigen::Vector3d& p, double c_p) const;
  bool inside_physical_box(const Eigen::Vector3d& p) const { return depth_into(p).isZero(0.0); }
};

}  // namespace rumble::fem
