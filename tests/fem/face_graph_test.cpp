// The graph PT-Scotch splits for the ranks (distributed/mesh_partition.hpp, face_graph; docs/
// fem-soil.md §8, "How the mesh is split"): the tetrahedra sharing a face, made from each node's
// tetrahedra, against PETSc's own DMPlexCreatePartitionerGraph on the same mesh, row by row in
// PETSc's order (PT-Scotch's split depends on it), and against its definition (symmetric, each
// pair sharing three nodes, the unshared faces the box's surface). This process starts PETSc
// (fem_gamg_tests).
#include <gtest/gtest.h>
#include <petscdmplex.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "mesh/kuhn_box.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {
namespace {

/// A Kuhn box whose tetrahedra are shuffled, each with its nodes turned (an even permutation,
/// so that it stays positively oriented): neither order is the box's regular one, as in gmsh's.
TetMesh shuffled_box() {
  TetMesh m = kuhn_box(4, 3, 2, 0.5);
  std::mt19937 random(7);
  std::shuffle(m.tets.begin(), m.tets.end(), random);
  for (Tetrahedron& t : m.tets) std::rotate(t.begin(), t.begin() + random() % 3, t.begin() + 3);
  return m;
}

/// PETSc's graph of the same mesh (a DMPlex of its tetrahedra and nodes, no faces).
FaceGraph petsc_graph(const TetMesh& m) {
  std::vector<PetscInt> cells;
  for (const Tetrahedron& t : m.tets) cells.insert(cells.end(), t.begin(), t.end());
  DM dm = nullptr;
  EXPECT_EQ(DMPlexCreateFromCellListPetsc(PETSC_COMM_SELF, 3, static_cast<PetscInt>(m.tets.size()),
                                          static_cast<PetscInt>(m.node_count()), 4, PETSC_FALSE,
                                          cells.data(), 3, m.nodes.data(), &dm),
            0);
  PetscInt vertices = 0;
  PetscInt* start = nullptr;
  PetscInt* adjacent = nullptr;
  EXPECT_EQ(DMPlexCreatePartitionerGraph(dm, 0, &vertices, &start, &adjacent, nullptr), 0);
  FaceGraph g{.start = std::vector<std::int32_t>(start, start + vertices + 1),
              .adjacent = std::vector<std::int32_t>(adjacent, adjacent + start[vertices])};
  PetscFree(start);
  PetscFree(adjacent);
  DMDestroy(&dm);
  return g;
}

int shared_nodes(const Tetrahedron& a, const Tetrahedron& b) {
  return static_cast<int>(std::count_if(a.begin(), a.end(), [&](std::int32_t v) {
    return std::find(b.begin(), b.end(), v) != b.end();
  }));
}

TEST(FaceGraph, IsPetscsPartitionerGraphInItsOrder) {
  const auto session = PetscSession::get();
  const TetMesh m = shuffled_box();
  const FaceGraph mine = face_graph(m), petsc = petsc_graph(m);
  EXPECT_EQ(mine.start, petsc.start);
  EXPECT_EQ(mine.adjacent, petsc.adjacent);
  // Sorted, the rows would be the same graph but another split (tests/mpi's runs differ).
  EXPECT_FALSE(std::is_sorted(mine.adjacent.begin() + mine.start[0],
                              mine.adjacent.begin() + mine.start[m.tets.size()]));
}

TEST(FaceGraph, JoinsTheTetrahedraThatShareAFace) {
  const TetMesh m = shuffled_box();
  const FaceGraph g = face_graph(m);
  ASSERT_EQ(g.start.size(), m.tets.size() + 1);
  for (std::size_t e = 0; e < m.tets.size(); ++e)
    for (std::int32_t k = g.start[e]; k < g.start[e + 1]; ++k) {
      const auto f = static_cast<std::size_t>(g.adjacent[k]);
      EXPECT_EQ(shared_nodes(m.tets[e], m.tets[f]), 3) << e << " " << f;
      const auto back = g.adjacent.begin();
      EXPECT_NE(std::find(back + g.start[f], back + g.start[f + 1], static_cast<std::int32_t>(e)),
                back + g.start[f + 1]);
    }
  // The faces on no other tetrahedron: the box's surface, two triangles per square of 0.5 m.
  const std::size_t surface = 2 * 2 * (4 * 3 + 4 * 2 + 3 * 2);
  EXPECT_EQ(4 * m.tets.size() - g.adjacent.size(), surface);
}

}  // namespace
}  // namespace rumble::fem
