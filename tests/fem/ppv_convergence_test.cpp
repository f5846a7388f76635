// A receiver's peak particle velocity converging under mesh refinement (issue #9): the same load
// on three meshes whose element sizes are h, h / sqrt(2) and h / 2 everywhere, the PPV (largest
// |v_z|) of surface receivers 3 m from the footprint. Linear tetrahedra with a lumped mass
// converge as h^2 (their dispersion and interpolation errors are O((k h)^2), the explicit step's
// O(dt^2) with dt ~ h): the difference between successive meshes must shrink, by about 2 for
// order 2 (ratio sqrt(2)).
//
// gmsh's meshes of different sizes are not nested, and where a receiver falls in its
// tetrahedron is a matter of chance: the linear interpolation's error (h^2 / 8 of the field's
// curvature, about 1 % at h = 0.6 m and 3 m from the load) varies between receivers and meshes.
// Four receivers at the same distance on the footprint's axes (the same PPV in the continuum)
// measure it (their spread) and their mean reduces it; the order from three meshes remains
// indicative (the finer meshes, h / 2 sqrt(2), are in the validation suite: validation_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "receiver_ppv.hpp"
#include "sanitizer.hpp"

namespace rumble::test {
namespace {

TEST(FemConvergence, ReceiverPpvConvergesUnderMeshRefinement) {
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  // Measured: mean PPV 9.991e-5, 1.0134e-4, 1.0183e-4 m/s for h = 0.6, 0.42, 0.3 m (8, 12 and
  // 16 elements per Rayleigh wavelength at 75 Hz, the end of the main lobe of the 20 ms rise's
  // velocity spectrum); differences 1.43e-6 then 4.8e-7 (3.0x: observed order 3.1; meshes of
  // 0.3 m that differ by a rounding of h gave 4.6e-7, order 3.2); the four receivers' spread
  // 8e-7, 4e-7, 2.4e-7. Bounds: the differences shrink by more than order 1.5 would
  // (sqrt(2)^1.5 = 1.68), the order lies in [1.5, 4.5], the last difference and the spread are
  // below 1 %.
  const double h = 0.6, r = std::sqrt(2.0);
  const RingPpv coarse = ring_ppv(h, 3.0, 8.0, 0.02, 0.03);
  const RingPpv medium = ring_ppv(h / r, 3.0, 8.0, 0.02, 0.03);
  const RingPpv fine = ring_ppv(h / 2.0, 3.0, 8.0, 0.02, 0.03);
  const double p1 = coarse.mean(), p2 = medium.mean(), p3 = fine.mean();
  const double order = observed_order(p1, p2, p3, r);
  RecordProperty("ppv_mean_h", std::to_string(p1));
  RecordProperty("ppv_mean_h_over_sqrt2", std::to_string(p2));
  RecordProperty("ppv_mean_h_over_2", std::to_string(p3));
  RecordProperty("observed_order", std::to_string(order));
  std::printf("PPV %.5e %.5e %.5e m/s (spread %.2e %.2e %.2e), differences %.3e %.3e, order %.2f\n",
              p1, p2, p3, coarse.spread(), medium.spread(), fine.spread(), std::abs(p2 - p1),
              std::abs(p3 - p2), order);
  EXPECT_LT(std::abs(p3 - p2), std::abs(p2 - p1) / std::pow(r, 1.5));
  EXPECT_GT(order, 1.5);
  EXPECT_LT(order, 4.5);
  EXPECT_LT(std::abs(p3 - p2), 0.01 * p3);
  EXPECT_LT(fine.spread(), 0.01 * p3);
}

}  // namespace
}  // namespace rumble::test
