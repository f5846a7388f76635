// What the msh fuzz targets check for one input (a gmsh mesh file a FEM soil names as
// mesh.file), shared by the libFuzzer targets (fuzz_target.cpp, preset "fuzz") and the replay
// test of the other presets (replay_test.cpp).
#pragma once

#include <string>
#include <string_view>

#include "fem_settings.hpp"

namespace rumble::fuzz {

/// The settings a .msh is read with: a half-space, no layers, and the schema's default limits
/// (mesh.max_dofs read from the FEM soil's schema, fem_schema.cpp, not repeated).
fem::FemSettings msh_default_settings();

/// Reads the sections $PhysicalNames, $Nodes and $Elements of `text` leniently, as MSH 2.2
/// writes them, and writes what they describe back as a well-formed MSH 2.2 file (names of
/// dimension 2 and 3, elements of the types a soil mesh may hold with their number of nodes,
/// each node defined, tags up to 1e6; coordinates as they are, "nan" and 1e308 included), which
/// it then checks as check_raw_msh_text does. gmsh's parser crashes on malformed element
/// records (docs/fuzzing.md lists what a raw campaign found): this keeps the run in CI on what
/// Rumble does with any mesh gmsh returns.
std::string check_msh_text(std::string_view text);

/// Writes `text` as it is as the mesh file of this process and reads it as the FEM soil's
/// layout does (plugins/soils/fem: load_mesh_file, then check_mesh_footprints against one
/// sleeper of 2.6 m x 0.26 m at the origin), with a half-space's settings (no layers). gmsh parses
/// the file (the Debian library, not instrumented: its own defects are found only as crashes);
/// Rumble's code around it is. Returns "" when every property holds, else what broke:
///   - a refusal is a std::invalid_argument or std::runtime_error whose message starts with
///     "fem: params/mesh/file: '<the file>'" (or "fem: gmsh failed to", gmsh's own errors in a
///     call after the file was read), and nothing else escapes;
///   - a mesh read has tetrahedra, each of its node indices (tetrahedra, ground, truncation) is a
///     node of it, a layer per tetrahedron within the layers, finite coordinates, every
///     tetrahedron positively oriented (a flat one is refused by the stiffness assembly, which
///     is not run here), the ground at z = 0, and footprint rectangles with finite, ordered
///     sides.
std::string check_raw_msh_text(std::string_view text);

}  // namespace rumble::fuzz
