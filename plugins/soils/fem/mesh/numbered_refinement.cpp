// Numbers of a refined mesh's nodes from the coarse entities (mesh/numbered_refinement.hpp;
// docs/fem-soil.md §8).
#include "mesh/numbered_refinement.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "mesh/uniform_refinement.hpp"

namespace rumble::fem {
namespace {

/// A node's barycentric coordinates in its coarse tetrahedron, times n = 2^levels (sum n).
using Lattice = std::array<int, 4>;
using TetLattice = std::array<Lattice, 4>;  // per node of a fine tetrahedron

/// The edge of a tetrahedron's nodes i < j, in refine_uniformly's order 01 02 03 12 13 23.
constexpr std::array<std::array<int, 4>, 4> kEdgeSlot = {
    {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}}};

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(hi) << 32U) | lo;
}

struct FaceHash {
  std::size_t operator()(const std::array<std::int32_t, 3>& f) const {
    return std::hash<std::uint64_t>()(edge_key(f[0], f[1]) * 0x9E3779B97F4A7C15ULL ^
                                      static_cast<std::uint32_t>(f[2]));
  }
};

/// The lattice points (x, y), x, y >= 1, x + y <= n - 1, before (x, y) in lexical order.
std::int64_t pair_index(int x, int y, int n) {
  std::int64_t q = y - 1;
  for (int i = 1; i < x; ++i) q += n - 1 - i;
  return q;
}

/// The points (i, j, l), each >= 1, i + j + l <= n - 1, before (i, j, l) in lexical order.
std::int64_t triple_index(int i, int j, int l, int n) {
  std::int64_t q = pair_index(j, l, n - i);
  for (int a = 1; a < i; ++a) q += static_cast<std::int64_t>(n - a - 1) * (n - a - 2) / 2;
  return q;
}

/// The number of the node at lattice point c of the part's coarse tetrahedron e (nodes t);
/// *seam: whether its entity's nodes are all on the seam.
std::int64_t lattice_number(const CoarseNames& names, const Tetrahedron& t, std::size_t e,
                            const Lattice& c, int n, const std::vector<char>& on_seam, char* seam) {
  std::array<int, 4> support{};
  int count = 0;
  for (int i = 0; i < 4; ++i)
    if (c[i] > 0) support[count++] = i;
  *seam = on_seam.empty() ? 0 : 1;
  for (int k = 0; k < count && *seam != 0; ++k) *seam = on_seam[t[support[k]]];
  const auto whole = [&](int i) { return names.node[t[i]]; };
  const std::int64_t edges_start = names.nodes, faces_start = edges_start + (n - 1) * names.edges,
                     face_points = static_cast<std::int64_t>(n - 1) * (n - 2) / 2,
                     tets_start = faces_start + face_points * names.faces;
  if (count == 1) return whole(support[0]);
  if (count == 2) {
    const int i = support[0], j = support[1], low = whole(i) < whole(j) ? i : j;
    return edges_start + (n - 1) * static_cast<std::int64_t>(names.edge[e][kEdgeSlot[i][j]]) +
           c[low] - 1;
  }
  if (count == 3) {
    const int opposite = 6 - support[0] - support[1] - support[2];
    std::sort(support.begin(), support.begin() + 3,
              [&](int a, int b) { return whole(a) < whole(b); });
    return faces_start + face_points * names.face[e][opposite] +
           pair_index(c[support[0]], c[support[1]], n);
  }
  const std::int64_t tet_points = static_cast<std::int64_t>(n - 1) * (n - 2) * (n - 3) / 6;
  return tets_start + tet_points * names.tet[e] + triple_index(c[0], c[1], c[2], n);
}

/// The lattice points of the fine tetrahedra's nodes from their parents' (children of parent p
/// are 8 p .. 8 p + 7, refine_uniformly's numbering; a new node the midpoint of `ends`).
std::vector<TetLattice> child_lattice(const TetMesh& coarse, const TetMesh& fine,
                                      const std::vector<std::array<std::int32_t, 2>>& ends,
                                      const std::vector<TetLattice>& at) {
  const auto first = static_cast<std::int32_t>(coarse.node_count());
  std::vector<TetLattice> out(fine.tets.size());
  for (std::size_t c = 0; c < fine.tets.size(); ++c) {
    const std::size_t p = c / 8;
    const auto in_parent = [&](std::int32_t v) -> const Lattice& {
      for (int a = 0; a < 4; ++a)
        if (coarse.tets[p][a] == v) return at[p][a];
      throw std::logic_error("fem: a refined tetrahedron's node is no node of its parent");
    };
    for (int a = 0; a < 4; ++a) {
      const std::int32_t v = fine.tets[c][a];
      if (v < first) {
        out[c][a] = in_parent(v);
        continue;
      }
      const Lattice &x = in_parent(ends[v - first][0]), &y = in_parent(ends[v - first][1]);
      for (int i = 0; i < 4; ++i) out[c][a][i] = (x[i] + y[i]) / 2;  // (even: see the header)
    }
  }
  return out;
}

}  // namespace

CoarseNames name_entities(const TetMesh& whole) {
  CoarseNames names;
  names.nodes = whole.node_count();
  names.tets = static_cast<std::int64_t>(whole.tets.size());
  names.node.resize(static_cast<std::size_t>(names.nodes));
  for (std::size_t i = 0; i < names.node.size(); ++i) names.node[i] = static_cast<std::int32_t>(i);
  names.tet.resize(whole.tets.size());
  for (std::size_t e = 0; e < whole.tets.size(); ++e) names.tet[e] = static_cast<std::int32_t>(e);
  std::unordered_map<std::uint64_t, std::int32_t> edges;
  std::unordered_map<std::array<std::int32_t, 3>, std::int32_t, FaceHash> faces;
  edges.reserve(whole.tets.size() * 2);
  faces.reserve(whole.tets.size() * 3);
  names.edge.resize(whole.tets.size());
  names.face.resize(whole.tets.size());
  for (std::size_t e = 0; e < whole.tets.size(); ++e) {
    const Tetrahedron& t = whole.tets[e];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        names.edge[e][kEdgeSlot[i][j]] =
            edges.try_emplace(edge_key(t[i], t[j]), static_cast<std::int32_t>(edges.size()))
                .first->second;
    for (int o = 0; o < 4; ++o) {
      std::array<std::int32_t, 3> key{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != o) key[k++] = t[a];
      std::sort(key.begin(), key.end());
      names.face[e][o] =
          faces.try_emplace(key, static_cast<std::int32_t>(faces.size())).first->second;
    }
  }
  names.edges = static_cast<std::int64_t>(edges.size());
  names.faces = static_cast<std::int64_t>(faces.size());
  return names;
}

RefinedCounts refined_counts(const CoarseNames& names, int levels) {
  const std::int64_t n = std::int64_t{1} << levels;
  return {names.nodes + (n - 1) * names.edges + (n - 1) * (n - 2) / 2 * names.faces +
              (n - 1) * (n - 2) * (n - 3) / 6 * names.tets,
          names.tets * n * n * n};
}

NumberedRefinement refine_numbered(const TetMesh& part, const CoarseNames& names, int levels,
                                   const std::vector<char>& on_seam) {
  if (levels < 1 || levels > 3)
    throw std::invalid_argument("refine_numbered: " + std::to_string(levels) +
                                " levels; give 1 to 3");
  const int n = 1 << levels;
  std::vector<TetLattice> at(part.tets.size());
  for (TetLattice& t : at)
    for (int a = 0; a < 4; ++a) t[a] = {}, t[a][a] = n;
  NumberedRefinement out;
  out.mesh = part;
  for (int level = 0; level < levels; ++level) {
    std::vector<std::array<std::int32_t, 2>> ends;
    TetMesh fine = refine_uniformly(out.mesh, &ends);
    at = child_lattice(out.mesh, fine, ends, at);
    out.mesh = std::move(fine);
  }
  out.number.assign(static_cast<std::size_t>(out.mesh.node_count()), -1);
  out.on_seam.assign(out.number.size(), 0);
  for (std::size_t c = 0; c < out.mesh.tets.size(); ++c) {
    const std::size_t e = c >> (3 * levels);  // (its coarse tetrahedron)
    for (int a = 0; a < 4; ++a) {
      const std::int32_t v = out.mesh.tets[c][a];
      char seam = 0;
      const std::int64_t number =
          lattice_number(names, part.tets[e], e, at[c][a], n, on_seam, &seam);
      if (out.number[v] >= 0 && out.number[v] != number)
        throw std::logic_error("fem: refined node " + std::to_string(v) + " numbered " +
                               std::to_string(out.number[v]) + " and " + std::to_string(number));
      out.number[v] = number;
      out.on_seam[v] = seam;
    }
  }
  return out;
}

}  // namespace rumble::fem
