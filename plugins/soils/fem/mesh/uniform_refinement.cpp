// Uniform refinement into eight (mesh/uniform_refinement.hpp; docs/fem-soil.md §2).
#include "mesh/uniform_refinement.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rumble::fem {
namespace {

/// The midpoint node of each edge of the mesh, numbered after the coarse nodes.
class EdgeMidpoints {
 public:
  explicit EdgeMidpoints(std::int32_t first) : next_(first) {}

  /// The midpoint of edge (a, b), made when first met.
  std::int32_t at(std::int32_t a, std::int32_t b) {
    const auto [it, added] = ids_.try_emplace(key(a, b), next_);
    if (added) {
      ends_.emplace_back(a, b);
      ++next_;
    }
    return it->second;
  }

  /// The midpoint of an edge already met; -1 when none.
  std::int32_t find(std::int32_t a, std::int32_t b) const {
    const auto it = ids_.find(key(a, b));
    return it == ids_.end() ? -1 : it->second;
  }

  const std::vector<std::pair<std::int32_t, std::int32_t>>& ends() const { return ends_; }

 private:
  static std::uint64_t key(std::int32_t a, std::int32_t b) {
    const auto lo = static_cast<std::uint32_t>(std::min(a, b));
    const auto hi = static_cast<std::uint32_t>(std::max(a, b));
    return (static_cast<std::uint64_t>(hi) << 32U) | lo;
  }

  std::int32_t next_;
  std::unordered_map<std::uint64_t, std::int32_t> ids_;
  std::vector<std::pair<std::int32_t, std::int32_t>> ends_;
};

/// Appends t to the fine mesh, positively oriented, with the parent's layer.
void add_child(TetMesh& fine, Tetrahedron t, std::uint16_t layer) {
  if (tet_volume(fine, t) < 0.0) std::swap(t[2], t[3]);
  fine.tets.push_back(t);
  fine.layer.push_back(layer);
}

/// The eight children of tetrahedron t whose edge midpoints are m (in the order 01, 02, 03, 12,
/// 13, 23). The octahedron's three diagonals join opposite midpoints (01-23, 02-13, 03-12); the
/// shortest is cut along, its four tetrahedra around it.
void split_tet(TetMesh& fine, const Tetrahedron& t, const std::array<std::int32_t, 6>& m,
               std::uint16_t layer) {
  add_child(fine, {t[0], m[0], m[1], m[2]}, layer);
  add_child(fine, {m[0], t[1], m[3], m[4]}, layer);
  add_child(fine, {m[1], m[3], t[2], m[5]}, layer);
  add_child(fine, {m[2], m[4], m[5], t[3]}, layer);
  constexpr std::array<std::array<int, 2>, 3> kDiagonals = {{{0, 5}, {1, 4}, {2, 3}}};
  int best = 0;
  double shortest = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double length =
        (fine.node(m[kDiagonals[d][0]]) - fine.node(m[kDiagonals[d][1]])).squaredNorm();
    if (d == 0 || length < shortest) best = d, shortest = length;
  }
  // The ring around the diagonal: the other two opposite pairs (p, q) and (r, s), in the cyclic
  // order p, r, q, s.
  const auto& p = kDiagonals[(best + 1) % 3];
  const auto& r = kDiagonals[(best + 2) % 3];
  const std::array<int, 4> ring = {p[0], r[0], p[1], r[1]};
  for (int i = 0; i < 4; ++i)
    add_child(fine,
              {m[kDiagonals[best][0]], m[kDiagonals[best][1]], m[ring[i]], m[ring[(i + 1) % 4]]},
              layer);
}

/// Each triangle into four, orientation kept; its edges' midpoints must exist.
std::vector<Triangle> split_triangles(const std::vector<Triangle>& faces,
                                      const EdgeMidpoints& midpoints, const char* surface) {
  std::vector<Triangle> fine;
  fine.reserve(4 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto [a, b, c] = faces[f];
    const std::int32_t ab = midpoints.find(a, b), bc = midpoints.find(b, c),
                       ca = midpoints.find(c, a);
    if (ab < 0 || bc < 0 || ca < 0)
      throw std::invalid_argument(std::string("refining the mesh: ") + surface + " triangle " +
                                  std::to_string(f) + " (nodes " + std::to_string(a) + ", " +
                                  std::to_string(b) + ", " + std::to_string(c) +
                                  ") is no face of a tetrahedron");
    fine.push_back({a, ab, ca});
    fine.push_back({ab, b, bc});
    fine.push_back({ca, bc, c});
    fine.push_back({ab, bc, ca});
  }
  return fine;
}

}  // namespace

TetMesh refine_uniformly(const TetMesh& coarse,
                         std::vector<std::array<std::int32_t, 2>>* midpoint_ends) {
  const auto first = static_cast<std::int32_t>(coarse.node_count());
  EdgeMidpoints midpoints(first);
  std::vector<std::array<std::int32_t, 6>> tet_midpoints(coarse.tets.size());
  for (std::size_t e = 0; e < coarse.tets.size(); ++e) {
    const Tetrahedron& t = coarse.tets[e];
    tet_midpoints[e] = {midpoints.at(t[0], t[1]), midpoints.at(t[0], t[2]),
                        midpoints.at(t[0], t[3]), midpoints.at(t[1], t[2]),
                        midpoints.at(t[1], t[3]), midpoints.at(t[2], t[3])};
  }
  TetMesh fine;
  fine.nodes.resize(3, first + static_cast<Eigen::Index>(midpoints.ends().size()));
  fine.nodes.leftCols(first) = coarse.nodes;
  for (std::size_t i = 0; i < midpoints.ends().size(); ++i) {
    const auto [a, b] = midpoints.ends()[i];
    fine.nodes.col(first + static_cast<Eigen::Index>(i)) = 0.5 * (coarse.node(a) + coarse.node(b));
  }
  fine.tets.reserve(8 * coarse.tets.size());
  fine.layer.reserve(8 * coarse.tets.size());
  for (std::size_t e = 0; e < coarse.tets.size(); ++e)
    split_tet(fine, coarse.tets[e], tet_midpoints[e], coarse.layer[e]);
  fine.ground = split_triangles(coarse.ground, midpoints, "ground");
  fine.truncation = split_triangles(coarse.truncation, midpoints, "truncation");
  if (midpoint_ends != nullptr) {
    midpoint_ends->clear();
    for (const auto& [a, b] : midpoints.ends()) midpoint_ends->push_back({a, b});
  }
  return fine;
}

TetMesh refine_uniformly(const TetMesh& coarse, int levels) {
  if (levels < 0)
    throw std::invalid_argument("refining the mesh: " + std::to_string(levels) +
                                " levels; give 0 or more");
  TetMesh mesh = coarse;
  for (int level = 0; level < levels; ++level) mesh = refine_uniformly(mesh);
  return mesh;
}

}  // namespace rumble::fem
