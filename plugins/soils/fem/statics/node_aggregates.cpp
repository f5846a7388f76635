#include "statics/node_aggregates.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace rumble::fem {

NodeGraph node_graph(const TetMesh& mesh) {
  const auto n = static_cast<std::int32_t>(mesh.node_count());
  NodeGraph g;
  // Each tetrahedron names 3 neighbours of each of its nodes: counted with repeats, filled,
  // then each row sorted and its repeats dropped in place.
  g.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const Tetrahedron& t : mesh.tets)
    for (const std::int32_t v : t) g.start[v + 1] += 3;
  for (std::int32_t i = 0; i < n; ++i) g.start[i + 1] += g.start[i];
  g.neighbours.resize(static_cast<std::size_t>(g.start[n]));
  std::vector<std::int64_t> next(g.start.begin(), g.start.end() - 1);
  for (const Tetrahedron& t : mesh.tets)
    for (const std::int32_t v : t)
      for (const std::int32_t w : t)
        if (w != v) g.neighbours[next[v]++] = w;
  std::int64_t kept = 0;
  for (std::int32_t i = 0; i < n; ++i) {
    const auto first = g.neighbours.begin() + g.start[i];
    const auto last = g.neighbours.begin() + g.start[i + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    g.start[i] = kept;
    kept = std::copy(first, end, g.neighbours.begin() + kept) - g.neighbours.begin();
  }
  g.start[n] = kept;
  g.neighbours.resize(static_cast<std::size_t>(kept));
  g.neighbours.shrink_to_fit();
  return g;
}

NodeGraph node_tetrahedra(const TetMesh& mesh) {
  const auto n = static_cast<std::int32_t>(mesh.node_count());
  NodeGraph g;
  g.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const Tetrahedron& t : mesh.tets)
    for (const std::int32_t v : t) ++g.start[v + 1];
  for (std::int32_t i = 0; i < n; ++i) g.start[i + 1] += g.start[i];
  g.neighbours.resize(static_cast<std::size_t>(g.start[n]));
  std::vector<std::int64_t> next(g.start.begin(), g.start.end() - 1);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)  // (each list ascending: e in order)
    for (const std::int32_t v : mesh.tets[e])
      g.neighbours[next[v]++] = static_cast<std::int32_t>(e);
  return g;
}

NodeGraph aggregate_members(const NodeAggregates& aggregates) {
  NodeGraph g;
  g.start.assign(static_cast<std::size_t>(aggregates.count) + 1, 0);
  for (const std::int32_t a : aggregates.of)
    if (a >= 0) ++g.start[a + 1];
  for (std::size_t a = 1; a < g.start.size(); ++a) g.start[a] += g.start[a - 1];
  g.neighbours.resize(static_cast<std::size_t>(g.start.back()));
  std::vector<std::int64_t> next(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < aggregates.of.size(); ++i)  // (each list ascending: i in order)
    if (aggregates.of[i] >= 0)
      g.neighbours[next[aggregates.of[i]]++] = static_cast<std::int32_t>(i);
  return g;
}

NodeAggregates aggregate_nodes(const NodeGraph& graph, const std::vector<char>& candidate) {
  const auto n = static_cast<std::int32_t>(candidate.size());
  NodeAggregates a;
  a.of.assign(candidate.size(), -1);
  const auto left = [&](std::int32_t j) { return candidate[j] && a.of[j] < 0; };
  // 1. roots whose candidate neighbours are all free: the root and those neighbours
  for (std::int32_t i = 0; i < n; ++i) {
    if (!left(i)) continue;
    const std::int32_t* w = graph.of(i);
    if (!std::all_of(w, w + graph.degree(i),
                     [&](std::int32_t j) { return !candidate[j] || left(j); }))
      continue;
    a.of[i] = a.count;
    for (std::int32_t k = 0; k < graph.degree(i); ++k)
      if (candidate[w[k]]) a.of[w[k]] = a.count;
    ++a.count;
  }
  // 2. each node left joins the first of its neighbours' aggregates of phase 1
  std::vector<std::int32_t> joins(candidate.size(), -1);
  for (std::int32_t i = 0; i < n; ++i) {
    if (!left(i)) continue;
    const std::int32_t* w = graph.of(i);
    const std::int32_t* found =
        std::find_if(w, w + graph.degree(i), [&](std::int32_t j) { return a.of[j] >= 0; });
    if (found != w + graph.degree(i)) joins[i] = a.of[*found];
  }
  for (std::int32_t i = 0; i < n; ++i)
    if (joins[i] >= 0) a.of[i] = joins[i];
  // 3. what is still left: each node and its neighbours still left
  for (std::int32_t i = 0; i < n; ++i) {
    if (!left(i)) continue;
    a.of[i] = a.count;
    for (std::int32_t k = 0; k < graph.degree(i); ++k)
      if (left(graph.of(i)[k])) a.of[graph.of(i)[k]] = a.count;
    ++a.count;
  }
  return a;
}

RigidProlongator rigid_prolongator(const Eigen::Matrix3Xd& nodes,
                                   const NodeAggregates& aggregates) {
  const std::size_t n = aggregates.of.size();
  const auto count = static_cast<std::size_t>(aggregates.count);
  RigidProlongator p;
  p.blocks.assign(3 * kModes * n, 0.0);
  p.modes.assign(kModes * kModes * count, 0.0);
  p.dropped.assign(kModes * count, 0);
  const NodeGraph members = aggregate_members(aggregates);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  qr.setThreshold(1e-9);  // (relative to the largest pivot: the modes are scaled to weigh alike)
  for (std::size_t a = 0; a < count; ++a) {
    const std::int32_t* node = members.of(static_cast<std::int32_t>(a));
    const auto m = static_cast<Eigen::Index>(members.degree(static_cast<std::int32_t>(a)));
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (Eigen::Index k = 0; k < m; ++k) c += nodes.col(node[k]);
    c /= static_cast<double>(m);
    double h = 0.0;  // the aggregate's size [m]: its farthest node from c
    for (Eigen::Index k = 0; k < m; ++k) h = std::max(h, (nodes.col(node[k]) - c).norm());
    if (h == 0.0) h = 1.0;
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3 * m, kModes);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Vector3d d = (nodes.col(node[k]) - c) / h;
      B.block<3, 3>(3 * k, 0).setIdentity();
      B(3 * k + 1, 3) = -d.z();  // about x
      B(3 * k + 2, 3) = d.y();
      B(3 * k, 4) = d.z();  // about y
      B(3 * k + 2, 4) = -d.x();
      B(3 * k, 5) = -d.y();  // about z
      B(3 * k + 1, 5) = d.x();
    }
    qr.compute(B);
    const Eigen::Index r = qr.rank();
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(3 * m, r);
    // B = Q R Pi^T: B's column j is Q times column j of R Pi^T (its first r rows)
    const Eigen::MatrixXd R = qr.matrixR().topRows(r).triangularView<Eigen::Upper>();
    // the whole mesh's rigid-body modes (about the origin) in B's columns: a translation t is
    // t; a rotation w is w x c plus the rotation (h w) about c
    Eigen::Matrix<double, kModes, kModes> global = Eigen::Matrix<double, kModes, kModes>::Zero();
    for (int j = 0; j < 3; ++j) {
      global(j, j) = 1.0;
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(j);
      global.block<3, 1>(0, 3 + j) = w.cross(c);
      global(3 + j, 3 + j) = h;
    }
    Eigen::Map<Eigen::Matrix<double, kModes, kModes>> out(p.modes.data() + kModes * kModes * a);
    out.topRows(r) = R * qr.colsPermutation().transpose() * global;
    for (Eigen::Index k = r; k < kModes; ++k) p.dropped[kModes * a + k] = 1;
    for (Eigen::Index k = 0; k < m; ++k)
      for (int row = 0; row < 3; ++row)
        for (Eigen::Index col = 0; col < r; ++col)
          p.blocks[3 * kModes * static_cast<std::size_t>(node[k]) + kModes * row + col] =
              Q(3 * k + row, col);
  }
  return p;
}

}  // namespace rumble::fem
