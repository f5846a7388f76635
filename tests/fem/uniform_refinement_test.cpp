// Uniform refinement into eight (mesh/uniform_refinement.hpp; issue #33, docs/fem-soil.md §2
// "mesh.refine"): the refined mesh fills the same volume and ground exactly, is conforming (each
// inner face shared by two tetrahedra, the boundary faces exactly the refined surfaces), has a
// node per coarse node and edge, keeps the quality bounded over three levels, and the settlement
// under a footing converges as the mesh is refined.
#include "mesh/uniform_refinement.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mesh/kuhn_box.hpp"
#include "operator/csr_matrix.hpp"
#include "operator/elasticity.hpp"
#include "sanitizer.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

double total_volume(const TetMesh& m) {
  double v = 0.0;
  for (const auto& t : m.tets) v += tet_volume(m, t);
  return v;
}

double total_area(const TetMesh& m, const std::vector<Triangle>& faces) {
  double a = 0.0;
  for (const auto& f : faces) a += triangle_area(m, f, nullptr);
  return a;
}

std::set<std::pair<std::int32_t, std::int32_t>> edges(const TetMesh& m) {
  std::set<std::pair<std::int32_t, std::int32_t>> e;
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) e.emplace(std::min(t[a], t[b]), std::max(t[a], t[b]));
  return e;
}

Triangle sorted(Triangle f) {
  std::sort(f.begin(), f.end());
  return f;
}

/// Quality 6 sqrt(2) V / l_rms^3: 1 for the regular tetrahedron, 0 for a flat one.
double quality(const TetMesh& m, const Tetrahedron& t) {
  double sum = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) sum += (m.node(t[a]) - m.node(t[b])).squaredNorm();
  return 6.0 * std::sqrt(2.0) * tet_volume(m, t) / std::pow(sum / 6.0, 1.5);
}

double min_quality(const TetMesh& m) {
  double q = 1.0;
  for (const auto& t : m.tets) q = std::min(q, quality(m, t));
  return q;
}

/// A Kuhn box with its inner nodes moved by up to 0.25 h (deterministic): unequal edges, so the
/// octahedra's diagonals differ.
TetMesh jittered_box(int n, double h) {
  TetMesh m = kuhn_box(n, h);
  unsigned state = 12345U;
  const auto next = [&state] {
    state = state * 1103515245U + 12345U;
    return static_cast<double>((state >> 8U) & 0xFFFFU) / 65535.0 - 0.5;  // [-0.5, 0.5]
  };
  for (Eigen::Index i = 0; i < m.node_count(); ++i) {
    const Eigen::Vector3d p = m.nodes.col(i);
    const bool inner = (p.array() > 1e-9).all() && (p.array() < n * h - 1e-9).all();
    const Eigen::Vector3d shift(next(), next(), next());
    if (inner) m.nodes.col(i) += 0.5 * h * shift;
  }
  return m;
}

TEST(FemUniformRefinement, FillsTheSameVolumeAndGroundWithANodePerEdge) {
  const TetMesh coarse = jittered_box(3, 0.5);
  const TetMesh fine = refine_uniformly(coarse);
  EXPECT_EQ(fine.node_count(),
            coarse.node_count() + static_cast<Eigen::Index>(edges(coarse).size()));
  EXPECT_EQ(fine.tets.size(), 8 * coarse.tets.size());
  EXPECT_EQ(fine.layer.size(), fine.tets.size());
  EXPECT_EQ(fine.ground.size(), 4 * coarse.ground.size());
  EXPECT_EQ(fine.truncation.size(), 4 * coarse.truncation.size());
  EXPECT_NEAR(total_volume(fine), total_volume(coarse), 1e-12 * total_volume(coarse));
  EXPECT_NEAR(total_volume(fine), 1.5 * 1.5 * 1.5, 1e-12);
  EXPECT_NEAR(total_area(fine, fine.ground), 1.5 * 1.5, 1e-12);
  EXPECT_NEAR(total_area(fine, fine.truncation), 5 * 1.5 * 1.5, 1e-12);
  for (const auto& t : fine.tets) ASSERT_GT(tet_volume(fine, t), 0.0);
  for (const auto& f : fine.ground)
    for (const auto i : f) ASSERT_EQ(fine.nodes(2, i), 0.0);
  // The coarse nodes keep their numbers and places.
  EXPECT_EQ(fine.nodes.leftCols(coarse.node_count()), coarse.nodes);
}

TEST(FemUniformRefinement, IsConformingAndItsBoundaryIsTheRefinedSurfaces) {
  const TetMesh fine = refine_uniformly(jittered_box(2, 1.0), 2);
  std::map<Triangle, int> faces;
  for (const auto& t : fine.tets)
    for (int skip = 0; skip < 4; ++skip) {
      Triangle f{};
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != skip) f[j++] = t[k];
      ++faces[sorted(f)];
    }
  std::set<Triangle> surface;
  for (const auto& f : fine.ground) surface.insert(sorted(f));
  for (const auto& f : fine.truncation) surface.insert(sorted(f));
  EXPECT_EQ(surface.size(), fine.ground.size() + fine.truncation.size());
  std::size_t boundary = 0;
  for (const auto& [f, count] : faces) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      ++boundary;
      ASSERT_TRUE(surface.count(f) == 1) << "a boundary face on no surface";
    }
  }
  EXPECT_EQ(boundary, surface.size());
}

TEST(FemUniformRefinement, KeepsTheLayersAndTheQualityBounded) {
  TetMesh coarse = jittered_box(3, 0.5);
  for (std::size_t e = 0; e < coarse.tets.size(); ++e) coarse.layer[e] = e % 3;
  const double q0 = min_quality(coarse);
  TetMesh mesh = coarse;
  for (int level = 1; level <= 3; ++level) {
    mesh = refine_uniformly(mesh);
    const double q = min_quality(mesh);
    std::printf("[ measured ] level %d: min quality %.4f (coarse %.4f), ratio %.3f\n", level, q, q0,
                q / q0);
    // The shortest diagonal: at most a few similarity classes per coarse tetrahedron (Bey),
    // so the ratio stops falling after the first level.
    EXPECT_GT(q, 0.5 * q0);
  }
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    ASSERT_EQ(mesh.layer[e], coarse.layer[e / 512]);  // children follow their parent, 8^3 each
}

/// Mean settlement [m] of a 2 m x 2 m footing under 100 kPa at the centre of the 4 m box's top,
/// its sides and bottom held: f . u / P, the compliance, which on nested meshes can only rise
/// (the finer space holds the coarser one).
double footing_settlement(const TetMesh& mesh) {
  const FemSettings settings = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  CsrMatrix k = assemble_stiffness(mesh, settings);
  std::vector<char> held(mesh.node_count(), 0);
  for (const auto& f : mesh.truncation)
    for (const auto i : f) held[i] = 1;
  std::vector<int> dof(3 * mesh.node_count(), -1);
  int free = 0;
  for (Eigen::Index i = 0; i < mesh.node_count(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!held[i]) dof[3 * i + c] = free++;
  std::vector<Eigen::Triplet<double>> entries;
  std::set<std::pair<std::int32_t, std::int32_t>> pairs = edges(mesh);
  for (std::int32_t i = 0; i < mesh.node_count(); ++i) pairs.emplace(i, i);
  const auto add_block = [&](std::int32_t i, std::int32_t j) {
    for (int c = 0; c < 3; ++c) {
      const double* row = k.block_row(i, j, c);
      for (int d = 0; d < 3; ++d)
        if (dof[3 * i + c] >= 0 && dof[3 * j + d] >= 0)
          entries.emplace_back(dof[3 * i + c], dof[3 * j + d], row[d]);
    }
  };
  for (const auto& [a, b] : pairs) {
    add_block(a, b);
    if (a != b) add_block(b, a);
  }
  Eigen::SparseMatrix<double> kf(free, free);
  kf.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(free);
  double load = 0.0;
  for (const auto& t : mesh.ground) {
    const Eigen::Vector3d centroid = (mesh.node(t[0]) + mesh.node(t[1]) + mesh.node(t[2])) / 3.0;
    if (std::abs(centroid.x() - 2.0) > 1.0 || std::abs(centroid.y() - 2.0) > 1.0) continue;
    const double force = 1e5 * triangle_area(mesh, t, nullptr);  // N, down (+z)
    load += force;
    for (const auto i : t)
      if (dof[3 * i + 2] >= 0) f[dof[3 * i + 2]] += force / 3.0;
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(kf);
  EXPECT_EQ(factor.info(), Eigen::Success);
  return f.dot(factor.solve(f)) / load;
}

TEST(FemUniformRefinement, AFootingsSettlementConvergesAsTheMeshIsRefined) {
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  const TetMesh coarse = kuhn_box(4, 1.0);
  const double s0 = footing_settlement(coarse);
  const double s1 = footing_settlement(refine_uniformly(coarse, 1));
  const double s2 = footing_settlement(refine_uniformly(coarse, 2));
  // The reference: an independent mesh of the finest size (Kuhn cubes of 0.25 m, not refined).
  const double reference = footing_settlement(kuhn_box(16, 0.25));
  std::printf(
      "[ measured ] settlement [mm]: %.5f coarse, %.5f refined once, %.5f twice, %.5f "
      "Kuhn 0.25 m; errors against it %.4f, %.4f, %.4f\n",
      1e3 * s0, 1e3 * s1, 1e3 * s2, 1e3 * reference, 1 - s0 / reference, 1 - s1 / reference,
      1 - s2 / reference);
  EXPECT_LT(s0, s1);  // nested spaces: the compliance rises
  EXPECT_LT(s1, s2);
  EXPECT_LT(std::abs(s1 - reference), 0.5 * std::abs(s0 - reference));
  EXPECT_LT(std::abs(s2 - reference), 0.5 * std::abs(s1 - reference));
}

/// The tetrahedra of `whole` listed in `tets` and their surface faces, numbered locally (nodes in
/// the order first met); `global` receives each local node's node in `whole`, `ground` each
/// local ground face's index in whole.ground.
TetMesh part_of(const TetMesh& whole, const std::vector<std::size_t>& tets,
                std::vector<std::int32_t>& global, std::vector<std::size_t>& ground) {
  TetMesh part;
  std::map<std::int32_t, std::int32_t> local;
  const auto node = [&](std::int32_t g) {
    const auto [it, added] = local.try_emplace(g, static_cast<std::int32_t>(global.size()));
    if (added) global.push_back(g);
    return it->second;
  };
  std::set<Triangle> faces;
  for (const std::size_t e : tets) {
    const Tetrahedron& t = whole.tets[e];
    part.tets.push_back({node(t[0]), node(t[1]), node(t[2]), node(t[3])});
    part.layer.push_back(whole.layer[e]);
    for (int skip = 0; skip < 4; ++skip) {
      Triangle f{};
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != skip) f[j++] = t[k];
      faces.insert(sorted(f));
    }
  }
  part.nodes.resize(3, static_cast<Eigen::Index>(global.size()));
  for (std::size_t i = 0; i < global.size(); ++i) part.nodes.col(i) = whole.node(global[i]);
  const auto localised = [&](const Triangle& f) {
    return Triangle{local.at(f[0]), local.at(f[1]), local.at(f[2])};
  };
  for (std::size_t f = 0; f < whole.ground.size(); ++f)
    if (faces.count(sorted(whole.ground[f])) == 1) {
      part.ground.push_back(localised(whole.ground[f]));
      ground.push_back(f);
    }
  return part;
}

// The rule the ranks would refine their parts by (docs/fem-soil.md §8, "Not yet"): a part refined
// alone, its new nodes named by their edges in the whole mesh, has exactly the children the whole
// mesh's refinement has, to the bit: nodes, tetrahedra, layers and ground faces.
TEST(FemUniformRefinement, APartRefinesIntoTheWholeRefinementsChildren) {
  TetMesh whole = jittered_box(4, 0.5);
  for (std::size_t e = 0; e < whole.tets.size(); ++e) whole.layer[e] = e % 2;
  std::vector<std::array<std::int32_t, 2>> whole_ends;
  const TetMesh fine = refine_uniformly(whole, &whole_ends);
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> fine_node_of_edge;
  for (std::size_t i = 0; i < whole_ends.size(); ++i)
    fine_node_of_edge[std::minmax(whole_ends[i][0], whole_ends[i][1])] =
        static_cast<std::int32_t>(whole.node_count() + static_cast<Eigen::Index>(i));
  std::vector<std::size_t> tets;  // the tetrahedra whose centroid lies at x < 0.8 m
  for (std::size_t e = 0; e < whole.tets.size(); ++e) {
    double x = 0.0;
    for (const auto v : whole.tets[e]) x += whole.nodes(0, v) / 4.0;
    if (x < 0.8) tets.push_back(e);
  }
  std::vector<std::int32_t> global;
  std::vector<std::size_t> ground;
  const TetMesh part = part_of(whole, tets, global, ground);
  ASSERT_GT(part.tets.size(), 50U);
  ASSERT_LT(part.tets.size(), whole.tets.size() / 2);
  std::vector<std::array<std::int32_t, 2>> ends;
  const TetMesh refined = refine_uniformly(part, &ends);
  std::vector<std::int32_t> fine_global = global;  // per node of the refined part
  for (const auto& [a, b] : ends)
    fine_global.push_back(fine_node_of_edge.at(std::minmax(global[a], global[b])));
  for (Eigen::Index i = 0; i < refined.node_count(); ++i)
    ASSERT_EQ(refined.nodes.col(i), fine.nodes.col(fine_global[i])) << "node " << i;
  for (std::size_t e = 0; e < tets.size(); ++e)
    for (std::size_t c = 0; c < 8; ++c) {
      const Tetrahedron& t = refined.tets[8 * e + c];
      const Tetrahedron mapped = {fine_global[t[0]], fine_global[t[1]], fine_global[t[2]],
                                  fine_global[t[3]]};
      ASSERT_EQ(mapped, fine.tets[8 * tets[e] + c]) << "child " << c << " of tetrahedron " << e;
      ASSERT_EQ(refined.layer[8 * e + c], fine.layer[8 * tets[e] + c]);
    }
  ASSERT_FALSE(ground.empty());
  for (std::size_t f = 0; f < ground.size(); ++f)
    for (std::size_t c = 0; c < 4; ++c) {
      const Triangle& t = refined.ground[4 * f + c];
      const Triangle mapped = {fine_global[t[0]], fine_global[t[1]], fine_global[t[2]]};
      ASSERT_EQ(mapped, fine.ground[4 * ground[f] + c]);
    }
}

TEST(FemUniformRefinement, RefusesASurfaceTriangleThatIsNoFace) {
  TetMesh m = kuhn_box(2, 1.0);
  m.truncation.push_back({0, 2, 8});  // the corners of a side's diagonal: no edge 0-8
  try {
    (void)refine_uniformly(m);
    FAIL() << "refined a mesh whose surface triangle is no face";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("truncation triangle"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)refine_uniformly(kuhn_box(1, 1.0), -1), std::invalid_argument);
}

}  // namespace
}  // namespace rumble::fem
