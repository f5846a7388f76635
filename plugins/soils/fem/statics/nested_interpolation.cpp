#include "statics/nested_interpolation.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rumble::fem {

namespace {

/// A fine node's place in its coarse tetrahedron: the lattice's numerators of its 4 barycentric
/// coordinates (of `steps` = 2^levels), or an exception when it is off the lattice.
std::array<int, 4> lattice_point(const Eigen::Matrix3d& to_barycentric, const Eigen::Vector3d& x0,
                                 const Eigen::Vector3d& x, int steps, std::int64_t coarse_tet) {
  const Eigen::Vector3d l = to_barycentric * (x - x0);
  const std::array<double, 4> lambda = {1.0 - l.sum(), l[0], l[1], l[2]};
  std::array<int, 4> m{};
  int sum = 0;
  for (int i = 0; i < 4; ++i) {
    const double scaled = lambda[i] * steps;
    m[i] = static_cast<int>(std::lround(scaled));
    // (rounding of the coordinates: far below a lattice step, which is 2^-levels of an edge)
    if (std::abs(scaled - m[i]) > 1e-6 || m[i] < 0) {
      std::ostringstream e;
      e << "fem: the refined mesh is not nested in the coarse one: a node of coarse "
           "tetrahedron "
        << coarse_tet << "'s children lies at barycentric coordinate " << lambda[i]
        << ", off the lattice of step 1/" << steps;
      throw std::invalid_argument(e.str());
    }
    sum += m[i];
  }
  if (sum != steps)
    throw std::invalid_argument(
        "fem: the refined mesh is not nested in the coarse one "
        "(barycentric coordinates not summing to 1)");
  return m;
}

}  // namespace

RowSparse nested_interpolation(const TetMesh& coarse, const TetMesh& fine, int levels) {
  const std::int64_t children = std::int64_t{1} << (3 * levels);  // 8^levels
  const int steps = 1 << levels;
  if (static_cast<std::int64_t>(fine.tets.size()) !=
      children * static_cast<std::int64_t>(coarse.tets.size())) {
    std::ostringstream e;
    e << "fem: a mesh of " << fine.tets.size() << " tetrahedra is no " << levels
      << "-fold refinement of one of " << coarse.tets.size();
    throw std::invalid_argument(e.str());
  }
  std::vector<char> placed(static_cast<std::size_t>(fine.node_count()), 0);
  std::vector<Eigen::Triplet<double, int>> weights;
  weights.reserve(static_cast<std::size_t>(2 * fine.node_count()));
  for (std::size_t e = 0; e < coarse.tets.size(); ++e) {
    const Tetrahedron& t = coarse.tets[e];
    const Eigen::Vector3d x0 = coarse.node(t[0]);
    Eigen::Matrix3d edges;
    for (int i = 0; i < 3; ++i) edges.col(i) = coarse.node(t[i + 1]) - x0;
    const Eigen::Matrix3d to_barycentric = edges.inverse();
    for (std::int64_t c = 0; c < children; ++c)
      for (const std::int32_t v : fine.tets[static_cast<std::size_t>(children * e + c)]) {
        if (placed[v]) continue;  // (its weights are the same from every tetrahedron around it)
        placed[v] = 1;
        const std::array<int, 4> m =
            lattice_point(to_barycentric, x0, fine.node(v), steps, static_cast<std::int64_t>(e));
        for (int i = 0; i < 4; ++i)
          if (m[i] != 0) weights.emplace_back(v, t[i], static_cast<double>(m[i]) / steps);
      }
  }
  RowSparse p(fine.node_count(), coarse.node_count());
  p.setFromTriplets(weights.begin(), weights.end());
  p.makeCompressed();
  return p;
}

}  // namespace rumble::fem
