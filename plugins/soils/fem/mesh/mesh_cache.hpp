// Meshes kept on disk by a hash of what determines them (the plan's sizes and domain, the
// layer interfaces, the footprints, the algorithm, gmsh's version), so that validate-then-run
// and the runs of a study that share a soil mesh once. Files are written whole and renamed into
// place, carry a checksum, and are checked on reading; a file that fails any check is ignored
// and the mesh made again.
#pragma once

#include <filesystem>
#include <optional>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/mesh_generator.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// $RUMBLE_MESH_CACHE (a directory; "off" or "" disables the cache), else
/// $XDG_CACHE_HOME/rumble/meshes, else $HOME/.cache/rumble/meshes; none without a home.
std::optional<std::filesystem::path> mesh_cache_directory();

/// The file name (hex hash + ".mesh") of the mesh these inputs make.
std::string mesh_cache_name(const FemSettings& settings, const std::vector<Footprint>& footprints,
                            const MeshPlan& plan);

/// The mesh stored at path, or nothing when absent or not intact.
std::optional<TetMesh> read_cached_mesh(const std::filesystem::path& path);

/// Stores the mesh at path (directories created); false when it could not (the cache is an
/// optimisation: the caller carries on).
bool write_cached_mesh(const std::filesystem::path& path, const TetMesh& mesh);

}  // namespace rumble::fem
