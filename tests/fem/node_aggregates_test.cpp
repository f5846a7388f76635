// The aggregation multigrid's first level from the mesh (plugins/soils/fem/statics/
// node_aggregates.hpp): every candidate node in exactly one aggregate, each aggregate connected
// in the mesh's graph, no other node in any; the tentative prolongator orthonormal and exact on
// the rigid-body modes (P P^T u = u for a rigid motion u on the aggregated nodes), so that the
// coarse level carries them; an aggregate too small for six modes keeps what it can carry.
#include "statics/node_aggregates.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdlib>
#include <set>

#include "mesh/kuhn_box.hpp"

namespace rumble::fem {
namespace {

TEST(NodeAggregates, TheGraphIsTheTetrahedraNeighbours) {
  const TetMesh m = kuhn_box(3, 2, 2, 1.0);
  const NodeGraph g = node_graph(m);
  std::vector<std::set<std::int32_t>> expected(static_cast<std::size_t>(m.node_count()));
  for (const Tetrahedron& t : m.tets)
    for (const std::int32_t a : t)
      for (const std::int32_t b : t)
        if (a != b) expected[a].insert(b);
  for (std::int32_t i = 0; i < m.node_count(); ++i)
    EXPECT_EQ(std::set<std::int32_t>(g.of(i), g.of(i) + g.degree(i)), expected[i]) << i;
  EXPECT_TRUE(std::is_sorted(g.of(0), g.of(0) + g.degree(0)));
}

TEST(NodeAggregates, EachNodesTetrahedraAndEachAggregatesMembers) {
  const TetMesh m = kuhn_box(3, 2, 2, 1.0);
  const NodeGraph tets = node_tetrahedra(m);
  std::size_t listed = 0;
  for (std::int32_t i = 0; i < m.node_count(); ++i) {
    for (std::int32_t q = 0; q < tets.degree(i); ++q) {
      const Tetrahedron& t = m.tets[static_cast<std::size_t>(tets.of(i)[q])];
      EXPECT_NE(std::find(t.begin(), t.end(), i), t.end()) << i;
    }
    EXPECT_TRUE(std::is_sorted(tets.of(i), tets.of(i) + tets.degree(i)));
    listed += static_cast<std::size_t>(tets.degree(i));
  }
  EXPECT_EQ(listed, 4 * m.tets.size());  // (every tetrahedron once at each of its nodes)
  NodeAggregates a;
  a.of = {1, -1, 0, 1, 0};
  a.count = 2;
  const NodeGraph members = aggregate_members(a);
  EXPECT_EQ(members.start, (std::vector<std::int64_t>{0, 2, 4}));
  EXPECT_EQ(members.neighbours, (std::vector<std::int32_t>{2, 4, 0, 3}));
}

TEST(NodeAggregates, EveryCandidateInOneConnectedAggregate) {
  const TetMesh m = kuhn_box(6, 5, 4, 0.5);
  const NodeGraph g = node_graph(m);
  std::vector<char> candidate(static_cast<std::size_t>(m.node_count()), 1);
  for (std::int32_t i = 0; i < m.node_count(); ++i)
    if (m.nodes(2, i) > 1.9) candidate[i] = 0;  // (the held bottom, z = 2 m)
  const NodeAggregates a = aggregate_nodes(g, candidate);
  ASSERT_GT(a.count, 1);
  std::vector<std::vector<std::int32_t>> members(static_cast<std::size_t>(a.count));
  for (std::int32_t i = 0; i < m.node_count(); ++i) {
    if (!candidate[i]) {
      EXPECT_EQ(a.of[i], -1) << i;
      continue;
    }
    ASSERT_GE(a.of[i], 0) << i;
    ASSERT_LT(a.of[i], a.count);
    members[a.of[i]].push_back(i);
  }
  for (const std::vector<std::int32_t>& nodes : members) {  // connected: a walk reaches all
    ASSERT_FALSE(nodes.empty());
    std::set<std::int32_t> reached = {nodes.front()}, inside(nodes.begin(), nodes.end());
    std::vector<std::int32_t> next = {nodes.front()};
    while (!next.empty()) {
      const std::int32_t i = next.back();
      next.pop_back();
      for (std::int32_t k = 0; k < g.degree(i); ++k)
        if (inside.count(g.of(i)[k]) && reached.insert(g.of(i)[k]).second)
          next.push_back(g.of(i)[k]);
    }
    EXPECT_EQ(reached.size(), nodes.size());
  }
  EXPECT_EQ(aggregate_nodes(g, candidate).of, a.of);  // (the same, run after run)
}

TEST(NodeAggregates, TheProlongatorIsOrthonormalAndExactOnRigidMotions) {
  const TetMesh m = kuhn_box(6, 5, 4, 0.5);
  const NodeGraph g = node_graph(m);
  const std::vector<char> candidate(static_cast<std::size_t>(m.node_count()), 1);
  const NodeAggregates a = aggregate_nodes(g, candidate);
  const RigidProlongator p = rigid_prolongator(m.nodes, a);
  const Eigen::Index n = m.node_count(), coarse = kModes * a.count;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * n, coarse);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < kModes; ++k)
        P(3 * i + r, kModes * a.of[i] + k) = p.blocks[3 * kModes * i + kModes * r + k];
  Eigen::MatrixXd kept_identity = Eigen::MatrixXd::Identity(coarse, coarse);
  for (Eigen::Index k = 0; k < coarse; ++k)
    if (p.dropped[k]) kept_identity(k, k) = 0.0;
  EXPECT_LT((P.transpose() * P - kept_identity).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::Vector3d t(0.3, -1.2, 0.7), w(0.05, 0.4, -0.25);  // a rigid motion
  Eigen::VectorXd u(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) u.segment<3>(3 * i) = t + w.cross(m.nodes.col(i));
  EXPECT_LT((P * (P.transpose() * u) - u).cwiseAbs().maxCoeff(), 1e-12 * u.cwiseAbs().maxCoeff());
  // and the modes' coarse vectors give the whole mesh's rigid-body modes back (GAMG's near-null
  // space on the coarse level): the translation along x and the rotation about z
  for (const int j : {0, 5}) {
    Eigen::VectorXd x(coarse);
    for (std::int32_t agg = 0; agg < a.count; ++agg)
      x.segment<kModes>(kModes * agg) = Eigen::Map<const Eigen::Matrix<double, kModes, kModes>>(
                                            p.modes.data() + kModes * kModes * agg)
                                            .col(j);
    const Eigen::VectorXd v = P * x;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d expected =
          j == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ().cross(m.nodes.col(i));
      EXPECT_LT((v.segment<3>(3 * i) - expected).norm(), 1e-12) << "mode " << j << ", node " << i;
    }
  }
}

TEST(NodeAggregates, AnAggregateTooSmallForSixModesKeepsWhatItCarries) {
  Eigen::Matrix3Xd nodes(3, 3);
  nodes << 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;  // three nodes on a line, one alone
  NodeAggregates a;
  a.of = {0, 0, 1};
  a.count = 2;
  const RigidProlongator p = rigid_prolongator(nodes, a);
  // two nodes on the x axis: no rotation about x; one node: its three translations
  EXPECT_EQ(std::count(p.dropped.begin(), p.dropped.begin() + kModes, 1), 1);
  EXPECT_EQ(std::count(p.dropped.begin() + kModes, p.dropped.end(), 1), 3);
  for (int k = 0; k < kModes; ++k) {  // (a dropped column is zero on every node)
    if (!p.dropped[k]) continue;
    for (int node = 0; node < 2; ++node)
      for (int r = 0; r < 3; ++r) EXPECT_EQ(p.blocks[3 * kModes * node + kModes * r + k], 0.0);
  }
}

}  // namespace
}  // namespace rumble::fem
