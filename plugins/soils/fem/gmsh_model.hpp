// gmsh as the FEM soil uses it: one session at a time (gmsh keeps global state), its errors as
// exceptions, and the current model read into a TetMesh (z up in gmsh, ground at z = 0; depth
// down in the mesh). Both the generated meshes (mesh_generator.hpp) and the user's .msh files
// come through here.
#pragma once

#include <gmsh.h>

#include <stdexcept>
#include <string>

#include "fem_settings.hpp"
#include "tet_mesh.hpp"

namespace rumble::fem {

/// The gmsh session of one meshing: gmsh keeps global state, so one at a time per process, and
/// gmsh 4.8 throws std::string (toolchain.md §8.10), turned here into std::runtime_error.
class GmshSession {
 public:
  explicit GmshSession(unsigned threads) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::option::setNumber("General.NumThreads", threads);
    // Same input, same mesh: gmsh otherwise takes as many threads as OpenMP offers per stage.
    for (const char* stage :
         {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
      gmsh::option::setNumber(stage, threads);
    gmsh::model::add("soil");
  }
  ~GmshSession() { gmsh::finalize(); }
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

/// The current model's linear tetrahedra, their layers (from the depth of their centroid), and
/// the faces of its boundary: with by_physical_groups, those of the physical surfaces "ground"
/// and "absorbing" (and layers from physical volumes "layer_<k>" when there are any); otherwise
/// the surfaces that bound one volume, on the ground when all three nodes are at z = 0.
TetMesh read_model(const FemSettings& settings, bool by_physical_groups);

/// A user's gmsh mesh file (.msh, z up, ground at z = 0, physical surfaces "ground" and
/// "absorbing"). Throws std::invalid_argument naming params/mesh/file with what is missing.
TetMesh read_mesh_file(const FemSettings& settings, const std::string& path);

}  // namespace rumble::fem
