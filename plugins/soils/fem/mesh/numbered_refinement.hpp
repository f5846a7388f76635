// Numbers for the nodes of a refined mesh that any part of the coarse mesh computes alike
// (issue #33; docs/fem-soil.md §8 "mesh.refine on the ranks"): after k uniform refinements
// (uniform_refinement.hpp) every node of the fine mesh lies at a point of the lattice of step
// 2^-k of a coarse tetrahedron's barycentric coordinates (each level adds edge midpoints, and the
// octahedron's three diagonals share their midpoint, so the diagonal chosen does not matter).
// Named by the coarse entity whose interior holds it (a node, an edge, a face or a tetrahedron,
// each by its number in the whole coarse mesh) and its lattice point there, in the entity's
// nodes ordered by their whole numbers, a fine node has one number on every rank that holds it:
//
//   coarse node g                 g
//   edge e, point q of n - 1      V + (n - 1) e + q
//   face f, point q of Pf         V + (n - 1) E + Pf f + q
//   tetrahedron t, point q of Pt  V + (n - 1) E + Pf F + Pt t + q
//
// with n = 2^k, Pf = (n - 1)(n - 2)/2 and Pt = (n - 1)(n - 2)(n - 3)/6 interior points of a face
// and a tetrahedron, and V, E, F the whole coarse mesh's nodes, edges and faces: the numbers
// are 0 .. V + (n - 1) E + Pf F + Pt T - 1, each once (the fine mesh's node count).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// The whole coarse mesh's names for the entities of a part of it (or of all of it).
struct CoarseNames {
  std::vector<std::int32_t> node;                 // per node of the part: its whole number
  std::vector<std::int32_t> tet;                  // per tetrahedron: its whole number
  std::vector<std::array<std::int32_t, 6>> edge;  // per tetrahedron: edges 01 02 03 12 13 23
  std::vector<std::array<std::int32_t, 4>> face;  // per tetrahedron: the face opposite node i
  std::int64_t nodes = 0, edges = 0, faces = 0, tets = 0;  // the whole coarse mesh's
};

/// The whole mesh's edges and faces numbered in the order first met over its tetrahedra (edges
/// in refine_uniformly's order 01 02 03 12 13 23, faces opposite nodes 0 1 2 3), with the
/// identity for its nodes and tetrahedra.
CoarseNames name_entities(const TetMesh& whole);

/// The fine mesh's node and tetrahedron counts after `levels` refinements of a mesh of these
/// counts (whole: V, E, F and T of the formula above).
struct RefinedCounts {
  std::int64_t nodes = 0, tets = 0;
};
RefinedCounts refined_counts(const CoarseNames& names, int levels);

struct NumberedRefinement {
  TetMesh mesh;                      // refine_uniformly(part, levels), node for node
  std::vector<std::int64_t> number;  // per fine node: its number above
  /// per fine node: whether its coarse entity's nodes are all in `on_seam` (the caller's
  /// coarse nodes shared with other parts): only such fine nodes can be shared.
  std::vector<char> on_seam;
};

/// `levels` (1-3) refinements of `part` (refine_uniformly's, level by level) with each fine
/// node's number; on_seam: per coarse node of the part (empty: none). Throws std::logic_error
/// when two tetrahedra name one node differently (a bug, never the input's).
NumberedRefinement refine_numbered(const TetMesh& part, const CoarseNames& names, int levels,
                                   const std::vector<char>& on_seam = {});

}  // namespace rumble::fem
