// What the readers of a gmsh model share (gmsh_model.cpp, msh_import.cpp, msh_footprints.cpp): the
// model's physical groups by name, how their messages list names and the file, and the read by
// physical groups. Private to the mesh room's gmsh files: the rest of the soil goes through
// gmsh_model.hpp.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// Physical groups of dimension dim by name (unnamed ones as "(unnamed, tag <tag>)").
std::map<std::string, int> physical_groups(int dim);

/// "\"a\", \"b\"" or "none".
std::string quoted_list(const std::vector<std::string>& names);

/// "fem: params/mesh/file: '<path>'", the start of every refusal of a mesh file.
std::string where_file(const std::string& path);

/// The current model read by its physical groups (checked present by the caller); the faces
/// of the physical surface "footprints" into footprint_faces when given.
TetMesh read_grouped(const FemSettings& s, const std::string& where,
                     std::vector<Triangle>* footprint_faces);

}  // namespace rumble::fem
