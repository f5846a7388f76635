// Where a receiver sits in the mesh: its tetrahedron and barycentric weights, so that its motion
// is the finite-element interpolation of the nodal motion (exact for linear elements).
#pragma once

#include <array>
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

}  // namespace rumble::fem
