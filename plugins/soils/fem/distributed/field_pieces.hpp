// A field snapshot on many ranks as a parallel VTU (issue #33; docs/fem-soil.md, "On many
// ranks"): each rank writes its part of the mesh (its tetrahedra and every node they touch) as
// one .vtu piece, the nodes it does not own marked as VTK's duplicate points (vtkGhostType 1),
// and rank 0 writes the .pvtu index naming the pieces (output/pvtu_writer.hpp). Nothing is
// gathered: each rank writes what it holds.
#pragma once

#include <string>

#include "distributed/distributed_soil.hpp"

namespace rumble::fem {

/// Writes the displacement (the static state plus the motion from it) [m] and the velocity
/// [m/s] at time t [s]: this rank's piece beside `pvtu` (piece_path) and, on rank 0, the index
/// at `pvtu`. Collective: a rank that cannot write stops every rank with its message.
void write_field_pieces(const DistributedSoil& soil, double t, const std::string& pvtu);

}  // namespace rumble::fem
