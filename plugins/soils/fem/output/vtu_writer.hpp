// A snapshot of the soil's nodal fields as a VTK unstructured grid (.vtu, XML, raw appended
// binary data: a 100k-node snapshot is 5 MB and opens in ParaView at once). z is the depth
// (down +), as everywhere in Rumble: ParaView shows the ground at the top with "z up" flipped.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// Writes displacement [m] and velocity [m/s] (3 per node) at time t [s] to path; throws
/// std::runtime_error naming the path when it cannot. ghosts (a piece of a parallel snapshot,
/// pvtu_writer.hpp): per node, VTK's vtkGhostType (0 a node the piece owns, 1 a copy of another
/// piece's node: VTK's DUPLICATEPOINT), written as that point array; null: none written.
void write_vtu(const std::string& path, double t, const TetMesh& mesh,
               const Eigen::VectorXd& displacement, const Eigen::VectorXd& velocity,
               const std::vector<std::uint8_t>* ghosts = nullptr);

}  // namespace rumble::fem
