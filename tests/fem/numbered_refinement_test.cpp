// Numbers of a refined mesh's nodes from the coarse entities (mesh/numbered_refinement.hpp;
// issue #33, docs/fem-soil.md §8 "mesh.refine on the ranks"): on the whole mesh they are each of
// 0 .. N - 1 once, N the refined mesh's node count (counted, and refined_counts' formula), the
// mesh refine_uniformly's node for node; a part refined alone numbers each of its nodes as the
// whole refinement numbers the node at the same point, for 1, 2 and 3 levels; one process's
// node order of a refined mesh is order_nodes_spatially's.
#include "mesh/numbered_refinement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <numeric>
#include <vector>

#include "mesh/kuhn_box.hpp"
#include "mesh/node_order.hpp"
#include "mesh/uniform_refinement.hpp"

namespace rumble::fem {
namespace {

/// A Kuhn box with its inner nodes moved by up to 0.25 h (deterministic), so that the
/// octahedra's diagonals differ.
TetMesh shaken_box(int n, double h) {
  TetMesh m = kuhn_box(n, h);
  unsigned state = 777U;
  const auto next = [&state] {
    state = state * 1103515245U + 12345U;
    return static_cast<double>((state >> 8U) & 0xFFFFU) / 65535.0 - 0.5;
  };
  for (Eigen::Index i = 0; i < m.node_count(); ++i) {
    const Eigen::Vector3d p = m.nodes.col(i);
    const Eigen::Vector3d shift(next(), next(), next());
    if ((p.array() > 1e-9).all() && (p.array() < n * h - 1e-9).all())
      m.nodes.col(i) += 0.5 * h * shift;
  }
  return m;
}

TEST(FemNumberedRefinement, NumbersTheWholeRefinementOnceEach) {
  const TetMesh whole = shaken_box(3, 0.5);
  const CoarseNames names = name_entities(whole);
  EXPECT_EQ(names.nodes - names.edges + names.faces - names.tets, 1);  // (Euler: a ball)
  for (int levels = 1; levels <= 3; ++levels) {
    const NumberedRefinement fine = refine_numbered(whole, names, levels);
    const TetMesh reference = refine_uniformly(whole, levels);
    ASSERT_EQ(fine.mesh.nodes, reference.nodes) << levels << " levels";
    ASSERT_EQ(fine.mesh.tets, reference.tets);
    const RefinedCounts counts = refined_counts(names, levels);
    EXPECT_EQ(counts.nodes, reference.node_count());
    EXPECT_EQ(counts.tets, static_cast<std::int64_t>(reference.tets.size()));
    std::vector<std::int64_t> sorted = fine.number;
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::int64_t> each(sorted.size());
    std::iota(each.begin(), each.end(), 0);
    EXPECT_EQ(sorted, each) << levels << " levels";
  }
}

TEST(FemNumberedRefinement, APartNumbersItsNodesAsTheWholeDoes) {
  const TetMesh whole = shaken_box(4, 0.5);
  const CoarseNames names = name_entities(whole);
  TetMesh part;  // the tetrahedra whose centroid lies at x < 0.8 m, nodes in the order met
  CoarseNames part_names = names;
  part_names.node.clear();
  part_names.tet.clear();
  part_names.edge.clear();
  part_names.face.clear();
  std::map<std::int32_t, std::int32_t> local;
  for (std::size_t e = 0; e < whole.tets.size(); ++e) {
    double x = 0.0;
    for (const auto v : whole.tets[e]) x += whole.nodes(0, v) / 4.0;
    if (x >= 0.8) continue;
    Tetrahedron t{};
    for (int a = 0; a < 4; ++a) {
      const auto [it, added] =
          local.try_emplace(whole.tets[e][a], static_cast<std::int32_t>(part_names.node.size()));
      if (added) part_names.node.push_back(whole.tets[e][a]);
      t[a] = it->second;
    }
    part.tets.push_back(t);
    part.layer.push_back(0);
    part_names.tet.push_back(static_cast<std::int32_t>(e));
    part_names.edge.push_back(names.edge[e]);
    part_names.face.push_back(names.face[e]);
  }
  part.nodes.resize(3, static_cast<Eigen::Index>(part_names.node.size()));
  for (std::size_t i = 0; i < part_names.node.size(); ++i)
    part.nodes.col(static_cast<Eigen::Index>(i)) = whole.node(part_names.node[i]);
  ASSERT_GT(part.tets.size(), 50U);
  ASSERT_LT(part.tets.size(), whole.tets.size() / 2);
  for (int levels = 1; levels <= 3; ++levels) {
    const NumberedRefinement fine = refine_numbered(whole, names, levels);
    std::vector<Eigen::Index> at(fine.number.size());  // the whole refinement's node per number
    for (std::size_t i = 0; i < fine.number.size(); ++i)
      at[fine.number[i]] = static_cast<Eigen::Index>(i);
    const NumberedRefinement mine = refine_numbered(part, part_names, levels);
    for (Eigen::Index i = 0; i < mine.mesh.node_count(); ++i)
      ASSERT_EQ(mine.mesh.nodes.col(i), fine.mesh.nodes.col(at[mine.number[i]]))
          << "node " << i << " of the part, " << levels << " levels";
  }
}

// One process's order of a refined mesh (fem_layout.cpp's refine_here: Morton keys, ties by
// number) is order_nodes_spatially's wherever no two nodes share a key: the mesh the explicit
// kernel steps is the one it stepped before the ranks refined their parts (§4.3's speed).
TEST(FemNumberedRefinement, OrdersTheNodesAsOrderNodesSpatially) {
  const TetMesh whole = shaken_box(3, 0.5);
  for (int levels = 1; levels <= 2; ++levels) {
    NumberedRefinement fine = refine_numbered(whole, name_entities(whole), levels);
    renumber_nodes(fine.mesh, numbered_spatial_order(fine.mesh.nodes, fine.number,
                                                     fine.mesh.nodes.rowwise().minCoeff(),
                                                     fine.mesh.nodes.rowwise().maxCoeff()));
    TetMesh reference = refine_uniformly(whole, levels);
    order_nodes_spatially(reference);
    EXPECT_EQ(fine.mesh.nodes, reference.nodes) << levels << " levels";
    EXPECT_EQ(fine.mesh.tets, reference.tets);
    EXPECT_EQ(fine.mesh.ground, reference.ground);
  }
}

TEST(FemNumberedRefinement, MarksTheNodesOnTheSeam) {
  const TetMesh whole = kuhn_box(2, 1.0);
  std::vector<char> seam(static_cast<std::size_t>(whole.node_count()), 0);
  for (Eigen::Index i = 0; i < whole.node_count(); ++i) seam[i] = whole.nodes(0, i) == 1.0;
  const NumberedRefinement fine = refine_numbered(whole, name_entities(whole), 2, seam);
  for (Eigen::Index i = 0; i < fine.mesh.node_count(); ++i)  // (the seam: the plane x = 1 m)
    EXPECT_EQ(fine.on_seam[i] != 0, fine.mesh.nodes(0, i) == 1.0) << "node " << i;
}

}  // namespace
}  // namespace rumble::fem
