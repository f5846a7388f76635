// gmsh as the FEM soil uses it: one session at a time (gmsh keeps global state), its errors as
// exceptions, and the current model read into a TetMesh (z up in gmsh, ground at z = 0; depth
// down in the mesh). Both the generated meshes (mesh_generator.hpp) and the user's .msh files
// come through here.
#pragma once

#include <gmsh.h>

#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// The gmsh session of one meshing: gmsh keeps global state, so one at a time per process, and
/// gmsh 4.8 throws std::string (docs/fem-soil.md §2), turned here into std::runtime_error. It reads
/// and writes no file of its own: no options or session file (~/.gmshrc, ~/.gmsh-options), no
/// preferences of the toolkit of its GUI, and its temporary file is never removed
/// (docs/fem-soil.md §2).
class GmshSession {
 public:
  explicit GmshSession(unsigned threads);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

template <class F>
auto gmsh_call(const char* what, F&& f) {
  try {
    return f();
  } catch (const std::string& message) {
    throw std::runtime_error(std::string("fem: gmsh failed to ") + what + ": " + message);
  }
}

/// The current model (a mesh the plugin generated) as linear tetrahedra, their layers (from the
/// depth of their centroid), and the faces of its boundary: the surfaces that bound one volume,
/// on the ground when all three nodes are at z = 0. (A user's mesh is read by its physical
/// groups instead: load_mesh_file.)
TetMesh read_model(const FemSettings& settings);

/// A footprint rectangle of a mesh file: the extent [m] and area [m^2] of one connected patch
/// of the physical surface "footprints" (frame of tet_mesh.hpp).
struct MeshFootprint {
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  double area = 0.0;
  double centre_x() const { return 0.5 * (x0 + x1); }
  double centre_y() const { return 0.5 * (y0 + y1); }
};

/// A user's mesh file as read: the mesh, the names of its physical surfaces, and the footprint
/// rectangles of its physical surface "footprints" (none when it has no such surface).
struct MeshFile {
  std::string path;
  TetMesh mesh;
  std::vector<std::string> surfaces;  // physical surface names, sorted
  bool has_footprints = false;
  std::vector<MeshFootprint> footprints;  // sorted by x, then y
};

/// The names a physical volume of a mesh file may have for layer k (k = layers.size(): the
/// half-space): the layer's name when it has one, "layer_<k>", and "half_space".
std::vector<std::string> mesh_layer_names(const FemSettings& settings, std::size_t k);

/// Reads a user's gmsh mesh file (docs/fem-soil.md §2: .msh, z up, ground at z = 0, linear
/// tetrahedra, physical surfaces "ground" and "absorbing", optionally "footprints" and physical
/// volumes named for the layers). Throws std::invalid_argument naming params/mesh/file with what
/// is wrong, what the file has, and the fix.
MeshFile load_mesh_file(const FemSettings& settings, const std::string& path);

/// load_mesh_file's mesh.
TetMesh read_mesh_file(const FemSettings& settings, const std::string& path);

/// Refuses a mesh file whose physical surface "footprints" is missing or whose rectangles are
/// not the track's footprints (count, centre and size within mesh_footprint_tolerance), with
/// what the file has, what the track has, and the fix.
void check_mesh_footprints(const MeshFile& file, const std::vector<Footprint>& footprints);

/// How far [m] a mesh file's footprint rectangle may lie from the track's (centre and each
/// side): 2 % of its smaller side, at least 1 mm.
double mesh_footprint_tolerance(const Footprint& footprint);

/// Writes mesh as a gmsh .msh (binary MSH 4.1, z up) with the physical groups load_mesh_file
/// reads: "ground", "footprints" (the ground faces inside a footprint), "absorbing", and a
/// physical volume per layer (its name, else "layer_<k>"; "half_space"). Element and face order
/// are kept, so that the file reads back as the same mesh.
void write_mesh_file(const TetMesh& mesh, const FemSettings& settings,
                     const std::vector<Footprint>& footprints, const std::string& path);

}  // namespace rumble::fem
