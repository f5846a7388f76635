#include "track/footprint_flexibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rumble {
namespace {

// Mean over a unit square of the potential 1/r of a uniform unit density on it:
// 4 (ln(1 + sqrt 2) - (sqrt 2 - 1) / 3) = 2.9732 (the square's side scales it as 1/side).
constexpr double kSquareSelfPotential = 2.97320;
// Cells per footprint along its shorter side: 2 puts the 1/r of neighbouring cells of one
// sleeper (0.13 m apart on a 0.26 m sleeper) at the resolution the iteration needs.
constexpr int kCellsAcrossShortSide = 2;

// Footprints whose centres are further apart than this many times their larger extent interact
// through 1/r between their centres: the mean of 1/r over the two differs from it by about
// (extent / d)^2 / 6, under 1 % there.
constexpr double kFarApart = 5.0;

struct Cell {
  double x, y;  // m, centre
};

/// The cells of one footprint: near-square, of equal area.
struct Cells {
  std::vector<Cell> at;
  double side = 0.0;  // m, side of the square of one cell's area
};

Cells cut(const rumble_footprint& p) {
  Cells cells;
  const double target = std::min(p.length, p.width) / kCellsAcrossShortSide;  // m
  const int along = std::max(1, static_cast<int>(std::lround(p.width / target)));
  const int across = std::max(1, static_cast<int>(std::lround(p.length / target)));
  const double dx = p.width / along, dy = p.length / across;  // m
  cells.side = std::sqrt(dx * dy);
  for (int a = 0; a < along; ++a)
    for (int b = 0; b < across; ++b)
      cells.at.push_back(
          {p.x - 0.5 * p.width + (a + 0.5) * dx, p.y - 0.5 * p.length + (b + 0.5) * dy});
  return cells;
}

/// Mean over cells a of the potential of a unit force spread over cells b [1/m].
double mean_potential(const Cells& a, const Cells& b, bool same) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.at.size(); ++i)
    for (std::size_t j = 0; j < b.at.size(); ++j)
      sum += same && i == j ? kSquareSelfPotential / a.side
                            : 1.0 / std::hypot(a.at[i].x - b.at[j].x, a.at[i].y - b.at[j].y);
  return sum / static_cast<double>(a.at.size() * b.at.size());
}

}  // namespace

Eigen::MatrixXd half_space_flexibility_shape(const std::vector<rumble_footprint>& footprints) {
  std::vector<Cells> cells;
  cells.reserve(footprints.size());
  for (const rumble_footprint& p : footprints) cells.push_back(cut(p));
  const auto n = static_cast<Eigen::Index>(footprints.size());
  Eigen::MatrixXd shape(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const rumble_footprint& p = footprints[static_cast<std::size_t>(i)];
    for (Eigen::Index j = i; j < n; ++j) {
      const rumble_footprint& q = footprints[static_cast<std::size_t>(j)];
      const double distance = std::hypot(p.x - q.x, p.y - q.y);  // m
      const double extent = std::max({p.length, p.width, q.length, q.width});
      shape(i, j) = shape(j, i) = distance > kFarApart * extent
                                      ? 1.0 / distance
                                      : mean_potential(cells[static_cast<std::size_t>(i)],
                                                       cells[static_cast<std::size_t>(j)], i == j);
    }
  }
  return shape;
}

}  // namespace rumble
