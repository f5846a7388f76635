// The band the mesh carries to a receiver (resolved_band.hpp): on a uniform Kuhn box it is
// c_R / (n h_mean) exactly, h_mean = (3 + 2 sqrt 2 + sqrt 3) / 6 a for cubes of edge a; where the
// path crosses coarser elements the band is theirs, found by locating every sample of the path
// one by one; a point beyond the mesh has none.
#include "frequency/resolved_band.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/kuhn_box.hpp"
#include "output/probe_locator.hpp"

namespace rumble::fem {
namespace {

constexpr double kCr = 169.0, kN = 10.0;  // m/s, elements per wavelength

double mean_edge_of(const TetMesh& m, const Tetrahedron& t) {
  double s = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) s += (m.node(t[a]) - m.node(t[b])).norm();
  return s / 6.0;
}

TEST(ResolvedBand, IsTheRuleOnAUniformMesh) {
  const double a = 0.5;
  const TetMesh box = kuhn_box(20, 20, 10, a);
  const TrackRegion track{1.0, 2.0, 1.0, 2.0};
  const auto f = path_resolved_frequency(box, track, {{5.0, 5.0, 0.0}, {8.0, 3.0, 2.0}}, kCr, kN);
  const double h_mean = (3.0 + 2.0 * std::sqrt(2.0) + std::sqrt(3.0)) / 6.0 * a;
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0], kCr / (kN * h_mean), 1e-9);
  EXPECT_NEAR(f[1], kCr / (kN * h_mean), 1e-9);
}

TEST(ResolvedBand, IsTheCoarsestElementOnThePath) {
  // Cubes of 1 m up to x = 5 m, stretched 2x in x beyond. (The reference below locates each of
  // the 128 samples anew: at 0.5 m it took 21 s under the sanitizers.)
  TetMesh box = kuhn_box(10, 10, 5, 1.0);
  for (Eigen::Index i = 0; i < box.nodes.cols(); ++i)
    if (box.nodes(0, i) > 5.0) box.nodes(0, i) = 5.0 + 2.0 * (box.nodes(0, i) - 5.0);
  const TrackRegion track{1.0, 2.0, 1.0, 2.0};
  const std::vector<Eigen::Vector3d> points{{4.5, 4.0, 0.0}, {12.0, 4.0, 1.0}};
  const auto f = path_resolved_frequency(box, track, points, kCr, kN);
  // Independently: locate each sample of each path and take the largest mean edge.
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector3d from(std::clamp(points[p].x(), 1.0, 2.0),
                               std::clamp(points[p].y(), 1.0, 2.0), 0.0);
    double largest = 0.0;
    for (int k = 0; k < kPathSamples; ++k) {
      const Eigen::Vector3d q = from + (points[p] - from) * (k / (kPathSamples - 1.0));
      largest =
          std::max(largest, mean_edge_of(box, locate_probe(box, q.x(), q.y(), q.z(), "q").nodes));
    }
    EXPECT_NEAR(f[p], kCr / (kN * largest), 1e-9 * f[p]) << p;
  }
  EXPECT_LT(f[1], 0.8 * f[0]);  // the far receiver sees the coarse elements
}

TEST(ResolvedBand, APointBeyondTheMeshHasNone) {
  const TetMesh box = kuhn_box(4, 1.0);
  const auto f =
      path_resolved_frequency(box, TrackRegion{0.0, 1.0, 0.0, 1.0}, {{40.0, 40.0, 30.0}}, kCr, kN);
  // The path starts inside the mesh: its first samples are resolved, the rest is not there.
  EXPECT_GT(f[0], 0.0);
  const auto none = path_resolved_frequency(box, TrackRegion{50.0, 51.0, 50.0, 51.0},
                                            {{60.0, 60.0, 0.0}}, kCr, kN);
  EXPECT_EQ(none[0], 0.0);
}

}  // namespace
}  // namespace rumble::fem
