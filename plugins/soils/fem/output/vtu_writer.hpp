// A snapshot of the soil's nodal fields as a VTK unstructured grid (.vtu, XML, raw appended
// binary data: a 100k-node snapshot is 5 MB and opens in ParaView at once). z is the depth
// (down +), as everywhere in Rumble: ParaView shows the ground at the top with "z up" flipped.
#pragma once

#include <Eigen/Core>
#include <string>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// Writes displacement [m] and velocity [m/s] (3 per node) at time t [s] to path; throws
/// std::runtime_error naming the path when it cannot.
void write_vtu(const std::string& path, double t, const TetMesh& mesh,
               const Eigen::VectorXd& displacement, const Eigen::VectorXd& velocity);

}  // namespace rumble::fem
