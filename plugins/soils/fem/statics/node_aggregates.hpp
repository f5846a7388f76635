// The first level of an aggregation multigrid for the statics, formed from the mesh alone (no
// assembled matrix): the nodes grouped into aggregates, and the tentative prolongator that maps
// each aggregate's six rigid-body modes onto its nodes (docs/fem-soil.md §8, "The statics on the
// ranks without an assembled matrix"). The ranks' matrix-free statics
// (distributed/aggregation_rank_statics.hpp) take these for their coarse level.
//
// Aggregation (Vanek, Mandel and Brezina's plain aggregation, its three phases; the graph is the
// mesh's, each node's neighbours the nodes it shares a tetrahedron with):
// 1. in node order, each candidate whose candidate neighbours are all free makes an aggregate of
//    itself and those neighbours;
// 2. each candidate left joins the first aggregate of phase 1 among its neighbours;
// 3. each candidate still left makes an aggregate of itself and its neighbours still left.
// The aggregates are numbered in the order they were made, so the same mesh and candidates give
// the same aggregates, run after run.
//
// The tentative prolongator: on aggregate a with nodes x_k and centroid c, the modes B_a (3 m x 6:
// the three translations, then the rotations about x, y and z through c, scaled by the
// aggregate's size so that the six columns weigh alike) factored B_a = Q_a R_a (column-pivoted
// QR). Q_a's columns are the aggregate's coarse DOFs (orthonormal: P^T P = I). An aggregate too
// small to carry six independent modes (one node, or nodes on a line) keeps the independent
// columns only; the others are marked dropped (their coarse DOFs carry nothing).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// A list per node (or aggregate) in compressed rows, ascending: the mesh's node graph (node i's
/// neighbours, itself excluded: node_graph), each node's tetrahedra (node_tetrahedra) or each
/// aggregate's nodes (aggregate_members).
struct NodeGraph {
  std::vector<std::int64_t> start;       // per node, and one past the last
  std::vector<std::int32_t> neighbours;  // start[i] to start[i + 1]: node i's
  std::int32_t degree(std::int32_t i) const {
    return static_cast<std::int32_t>(start[i + 1] - start[i]);
  }
  const std::int32_t* of(std::int32_t i) const { return neighbours.data() + start[i]; }
};

/// The neighbours of each node through the mesh's tetrahedra (about 60 B per node).
NodeGraph node_graph(const TetMesh& mesh);
/// The tetrahedra of each node (16 B per tetrahedron).
NodeGraph node_tetrahedra(const TetMesh& mesh);

/// Per node: its aggregate, or -1 where candidate[i] is 0 (such nodes join none and link none).
struct NodeAggregates {
  std::vector<std::int32_t> of;
  std::int32_t count = 0;
};
NodeAggregates aggregate_nodes(const NodeGraph& graph, const std::vector<char>& candidate);
/// Each aggregate's nodes, ascending, in compressed rows (of(a), degree(a)).
NodeGraph aggregate_members(const NodeAggregates& aggregates);

/// Six coarse DOFs per aggregate: aggregate a's are 6 a to 6 a + 5.
constexpr int kModes = 6;

/// The tentative prolongator of `aggregates` on the nodes' positions [m].
struct RigidProlongator {
  /// Per node: its 3 x 6 block of P (row-major: component, then the aggregate's coarse DOF);
  /// zeros on a node in no aggregate.
  std::vector<double> blocks;
  /// Per aggregate (6 x 6, column-major): the coarse vector of the whole mesh's rigid-body mode
  /// j (the translations along x, y, z, then the rotations about the axes through the origin)
  /// is column j on every aggregate, Q_a times it that mode on the aggregate's nodes.
  std::vector<double> modes;
  /// Per coarse DOF: 1 where the aggregate could not carry it (its column of P is zero).
  std::vector<char> dropped;
};
RigidProlongator rigid_prolongator(const Eigen::Matrix3Xd& nodes, const NodeAggregates& aggregates);

}  // namespace rumble::fem
