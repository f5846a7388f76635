// The mesh cache: a stored mesh reads back identical, other inputs give another name, and a
// damaged or foreign file is refused (read_cached_mesh returns nothing: the mesh is made again).
#include "mesh/mesh_cache.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "mesh/kuhn_box.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("rumble_mesh_cache_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(FemMeshCache, StoredMeshReadsBackIdentical) {
  const TetMesh m = kuhn_box(3, 0.5);
  const auto path = scratch("a/b/box.mesh");  // directories made as needed
  ASSERT_TRUE(write_cached_mesh(path, m));
  const auto back = read_cached_mesh(path);
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(back->nodes == m.nodes);
  EXPECT_EQ(back->tets, m.tets);
  EXPECT_EQ(back->layer, m.layer);
  EXPECT_EQ(back->ground, m.ground);
  EXPECT_EQ(back->truncation, m.truncation);
}

TEST(FemMeshCache, DamagedOrForeignFilesAreRefused) {
  const auto path = scratch("damaged.mesh");
  ASSERT_TRUE(write_cached_mesh(path, kuhn_box(2, 0.5)));
  {  // one byte changed in the middle
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(200);
    f.put('\x7f');
  }
  EXPECT_FALSE(read_cached_mesh(path).has_value());
  ASSERT_TRUE(write_cached_mesh(path, kuhn_box(2, 0.5)));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 9);  // cut short
  EXPECT_FALSE(read_cached_mesh(path).has_value());
  std::ofstream(path) << "not a mesh";
  EXPECT_FALSE(read_cached_mesh(path).has_value());
  EXPECT_FALSE(read_cached_mesh(scratch("absent.mesh")).has_value());
}

TEST(FemMeshCache, NameChangesWithWhatMakesTheMesh) {
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  const std::vector<Footprint> fp = {{0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}};
  const MeshPlan p = plan_mesh(s, fp);
  const std::string name = mesh_cache_name(s, fp, p);
  EXPECT_EQ(name, mesh_cache_name(s, fp, p));
  MeshPlan finer = p;
  finer.h_near *= 0.9;
  EXPECT_NE(name, mesh_cache_name(s, fp, finer));
  std::vector<Footprint> moved = fp;
  moved[1].x += 1e-9;
  EXPECT_NE(name, mesh_cache_name(s, moved, p));
  FemSettings layered = s;
  layered.layers.push_back({2.0, {50e6, 0.3, 1800.0}});
  EXPECT_NE(name, mesh_cache_name(layered, fp, p));
  FemSettings optimized = s;  // gmsh moves nodes of the tetrahedra below the quality threshold
  optimized.mesh.quality_threshold = 0.6;
  EXPECT_NE(name, mesh_cache_name(optimized, fp, p));
  FemSettings stiffer = s;  // a material alone does not change the mesh (h_near is in the plan)
  stiffer.half_space.E *= 2.0;
  EXPECT_EQ(name, mesh_cache_name(stiffer, fp, p));
}

TEST(FemMeshCache, DirectoryFromTheEnvironment) {
  ::setenv("RUMBLE_MESH_CACHE", "/some/where", 1);
  EXPECT_EQ(mesh_cache_directory(), std::filesystem::path("/some/where"));
  ::setenv("RUMBLE_MESH_CACHE", "off", 1);
  EXPECT_FALSE(mesh_cache_directory().has_value());
  ::unsetenv("RUMBLE_MESH_CACHE");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(mesh_cache_directory(), std::filesystem::path("/xdg/rumble/meshes"));
}

}  // namespace
}  // namespace rumble::fem
