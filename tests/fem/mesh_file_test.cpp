// A user's gmsh mesh (params/mesh/file): read with its physical groups, usable by the operators
// (footprint weights), and refused with a message naming what is missing.
#include <gmsh.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "expect_message.hpp"
#include "mesh/gmsh_model.hpp"
#include "operator/footprint_loads.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

/// A 6 x 4 x 3 m box (z up, ground at z = 0) with a 2.6 x 0.26 m footprint embedded at the
/// origin, written as .msh with the given physical surfaces; returns its path.
std::string write_box(const std::string& name, bool with_groups) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rumble_mesh_file_" + std::to_string(::getpid()) + "_" + name + ".msh");
  GmshSession session(1);
  namespace occ = gmsh::model::occ;
  const int box = occ::addBox(-3.0, -2.0, -3.0, 6.0, 4.0, 3.0);
  const int rect = occ::addRectangle(-0.13, -1.3, 0.0, 0.26, 2.6);
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  occ::fragment({{3, box}}, {{2, rect}}, out, map);
  occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.6);
  if (with_groups) {
    std::vector<int> ground, absorbing;
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    for (const auto& [dim, tag] : surfaces) {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
      // (OCC pads bounding boxes by its tolerance, 1e-7)
      (std::abs(z0) < 1e-6 && std::abs(z1) < 1e-6 ? ground : absorbing).push_back(tag);
    }
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, ground), "ground");
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, absorbing), "absorbing");
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    gmsh::model::addPhysicalGroup(3, {volumes.front().second});
  }
  gmsh::model::mesh::generate(3);
  gmsh::write(path.string());
  return path.string();
}

FemSettings medium_soil() {
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  return s;
}

TEST(FemMeshFile, AUsersMeshWithItsPhysicalGroups) {
  const TetMesh m = read_mesh_file(medium_soil(), write_box("good", true));
  ASSERT_GT(m.tets.size(), 100u);
  double volume = 0.0;
  for (const Tetrahedron& t : m.tets) {
    ASSERT_GT(tet_volume(m, t), 0.0);
    volume += tet_volume(m, t);
  }
  EXPECT_NEAR(volume, 72.0, 1e-9 * 72.0);
  double ground = 0.0, truncation = 0.0;
  for (const Triangle& f : m.ground) ground += triangle_area(m, f, nullptr);
  for (const Triangle& f : m.truncation) truncation += triangle_area(m, f, nullptr);
  EXPECT_NEAR(ground, 24.0, 1e-9);                            // the top, footprint included
  EXPECT_NEAR(truncation, 24.0 + 2 * 18.0 + 2 * 12.0, 1e-9);  // bottom and four sides
  const FootprintWeights w = footprint_weights(m, {{0.0, 0.0, 2.6, 0.26}});
  double sum = 0.0;
  for (const NodalWeight& nw : w[0]) sum += nw.weight;
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(FemMeshFile, MissingGroupsAndFilesAreNamed) {
  test::expect_invalid_argument_containing(
      [] { read_mesh_file(medium_soil(), write_box("bare", false)); },
      {"fem: params/mesh/file: '", "has no physical surface \"ground\" and \"absorbing\"",
       "(it has: none); name the free surface at z = 0 \"ground\""});
  test::expect_invalid_argument_containing(
      [] { read_mesh_file(medium_soil(), "/nonexistent/soil.msh"); },
      {"fem: params/mesh/file: '/nonexistent/soil.msh' is not a file"});
  const auto junk = std::filesystem::temp_directory_path() /
                    ("rumble_junk_" + std::to_string(::getpid()) + ".msh");
  std::ofstream(junk) << "$MeshFormat\nnonsense\n";
  test::expect_invalid_argument_containing([&] { read_mesh_file(medium_soil(), junk.string()); },
                                           {"gmsh cannot read it"});
}

}  // namespace
}  // namespace rumble::fem
