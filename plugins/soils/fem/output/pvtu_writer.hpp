// The index of a field snapshot written in pieces, one per rank (a VTK XML parallel unstructured
// grid, .pvtu; docs/fem-soil.md, "On many ranks"): it names each piece's .vtu (vtu_writer.hpp,
// with vtkGhostType marking the copies of shared nodes) and declares their arrays, so that
// ParaView or VTK's vtkXMLPUnstructuredGridReader opens the pieces as one grid.
#pragma once

#include <string>
#include <vector>

namespace rumble::fem {

/// Whether `path` names a snapshot in pieces (it ends in .pvtu: the host's convention on many
/// ranks, rumble/abi.h, write_fields).
bool is_parallel_snapshot(const std::string& path);

/// The file name of piece `rank` of the snapshot at `pvtu` (a path ending in .pvtu): the same
/// path with ".pvtu" replaced by "_<rank>.vtu", the host's convention (rumble/abi.h,
/// write_fields). Throws std::invalid_argument when pvtu does not end in .pvtu.
std::string piece_path(const std::string& pvtu, int rank);

/// Writes the index at `pvtu` naming `pieces` pieces (piece_path's names, relative to the
/// index's directory); throws std::runtime_error naming the path when it cannot.
void write_pvtu(const std::string& pvtu, int pieces);

}  // namespace rumble::fem
