#include "mesh/node_order.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

namespace rumble::fem {

namespace {

/// The bits of v (< 2^21) spread to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffff;
  v = (v | v << 16) & 0x1f0000ff0000ff;
  v = (v | v << 8) & 0x100f00f00f00f00f;
  v = (v | v << 4) & 0x10c30c30c30c30c3;
  v = (v | v << 2) & 0x1249249249249249;
  return v;
}

}  // namespace

std::vector<std::uint64_t> morton_keys(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& min,
                                       const Eigen::Vector3d& max) {
  // Halved coordinates (exactly: the keys are the same): a mesh file's nodes at +-1e308 made the
  // extent infinite, its scale 0 and 0 x inf a NaN key, no integer (found by the msh fuzz target).
  const Eigen::Vector3d lo = 0.5 * min, hi = 0.5 * max;
  const double scale = ((1 << 21) - 1) / std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::uint64_t> key(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::Vector3d q = (0.5 * points.col(i) - lo) * scale;
    key[static_cast<std::size_t>(i)] = spread_bits(static_cast<std::uint64_t>(q.x())) |
                                       spread_bits(static_cast<std::uint64_t>(q.y())) << 1 |
                                       spread_bits(static_cast<std::uint64_t>(q.z())) << 2;
  }
  return key;
}

std::vector<std::int32_t> numbered_spatial_order(const Eigen::Matrix3Xd& points,
                                                 const std::vector<std::int64_t>& number,
                                                 const Eigen::Vector3d& min,
                                                 const Eigen::Vector3d& max) {
  const std::vector<std::uint64_t> key = morton_keys(points, min, max);
  std::vector<std::int32_t> order(key.size());  // new index -> old
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return key[a] != key[b] ? key[a] < key[b] : number[a] < number[b];
  });
  return order;
}

std::vector<std::int32_t> spatial_order(const Eigen::Matrix3Xd& points) {
  const Eigen::Index n = points.cols();
  std::vector<std::int32_t> order(static_cast<std::size_t>(n));  // new index -> old
  if (n == 0) return order;
  const std::vector<std::uint64_t> key =
      morton_keys(points, points.rowwise().minCoeff(), points.rowwise().maxCoeff());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&key](std::int32_t a, std::int32_t b) {
    return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)];
  });
  return order;
}

void renumber_nodes(TetMesh& m, const std::vector<std::int32_t>& order,
                    std::vector<Triangle>* more_faces) {
  const Eigen::Index n = m.node_count();
  std::vector<std::int32_t> renamed(static_cast<std::size_t>(n));  // old index -> new
  Eigen::Matrix3Xd nodes(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::int32_t old = order[static_cast<std::size_t>(k)];
    renamed[static_cast<std::size_t>(old)] = static_cast<std::int32_t>(k);
    nodes.col(k) = m.nodes.col(old);
  }
  m.nodes = std::move(nodes);
  const auto rename = [&renamed](auto& cells) {
    for (auto& cell : cells)
      for (std::int32_t& v : cell) v = renamed[static_cast<std::size_t>(v)];
  };
  rename(m.tets);
  rename(m.ground);
  rename(m.truncation);
  if (more_faces != nullptr) rename(*more_faces);
}

void order_nodes_spatially(TetMesh& m, std::vector<Triangle>* more_faces) {
  if (m.node_count() == 0) return;
  renumber_nodes(m, spatial_order(m.nodes), more_faces);
}

}  // namespace rumble::fem
