// A linear tetrahedral mesh of the soil in the boundary's frame: x along the track, y across it,
// z the depth (positive downward, abi.h), all in metres. Produced by mesh_generator.hpp; the
// operators (assembly, boundary, loads, probes) read nothing else.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

namespace rumble::fem {

using Triangle = std::array<std::int32_t, 3>;
using Tetrahedron = std::array<std::int32_t, 4>;

struct TetMesh {
  Eigen::Matrix3Xd nodes;            // [m], column per node
  std::vector<Tetrahedron> tets;     // positively oriented (volume > 0)
  std::vector<std::uint16_t> layer;  // per tet: index into the layers, layers.size() = half-space
  std::vector<Triangle> ground;      // faces on the free surface z = 0 (footprints included)
  std::vector<Triangle> truncation;  // faces on the truncation surface (absorbing boundary)

  Eigen::Index node_count() const { return nodes.cols(); }
  Eigen::Index dof_count() const { return 3 * nodes.cols(); }
  Eigen::Vector3d node(std::int32_t i) const { return nodes.col(i); }
};

/// Signed volume of a tetrahedron [m^3] (> 0 when positively oriented).
inline double tet_volume(const TetMesh& m, const Tetrahedron& t) {
  const Eigen::Vector3d a = m.node(t[1]) - m.node(t[0]), b = m.node(t[2]) - m.node(t[0]),
                        c = m.node(t[3]) - m.node(t[0]);
  return a.dot(b.cross(c)) / 6.0;
}

/// Area [m^2] and unit normal (orientation as given) of a triangle.
inline double triangle_area(const TetMesh& m, const Triangle& f, Eigen::Vector3d* normal) {
  const Eigen::Vector3d n = (m.node(f[1]) - m.node(f[0])).cross(m.node(f[2]) - m.node(f[0]));
  const double twice = n.norm();
  if (normal != nullptr) *normal = n / twice;
  return 0.5 * twice;
}

}  // namespace rumble::fem
