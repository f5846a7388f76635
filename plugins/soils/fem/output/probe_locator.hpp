// Where a receiver sits in the mesh: its tetrahedron and barycentric weights, so that its motion
// is the finite-element interpolation of the nodal motion (exact for linear elements).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

struct ProbePoint {
  Tetrahedron nodes{};
  std::array<double, 4> weights{};  // barycentric, sum 1
};

/// The point (x, y, depth) [m]; throws std::invalid_argument naming `name` when it is outside
/// the mesh (beyond 1e-6 of an element's size).
ProbePoint locate_probe(const TetMesh& mesh, double x, double y, double depth,
                        const std::string& name);

/// locate_probe's search, for a mesh split over ranks (each rank searches its part, the best of
/// the ranks' wins): the tetrahedron whose smallest barycentric coordinate at the point is the
/// largest, the first in the mesh's order among equals; tet -1 when none is near.
struct ProbeCandidate {
  ProbePoint point;
  double smallest = -1e300;  // its smallest barycentric coordinate [-]
  std::int64_t tet = -1;     // its index in the mesh
  /// Whether the point lies in the tetrahedron (to 1e-6 of its size).
  bool inside() const { return smallest >= -1e-6; }
};
ProbeCandidate best_tetrahedron(const TetMesh& mesh, const Eigen::Vector3d& point);
/// The error of a receiver `name` at (x, y, depth) [m] outside the mesh.
[[noreturn]] void refuse_probe_outside(const std::string& name, double x, double y, double depth);

}  // namespace rumble::fem
