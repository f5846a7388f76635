// Static checks of the vehicle/track participant against closed forms (docs/physics.md §7, §8,
// §10 cases 3 and 6).
#include <gtest/gtest.h>

#include <cmath>

#include "track_fixture.hpp"

namespace rumble {
namespace {

using testing::make_track;
using testing::ref_a_track;
using testing::single_wheel;

// REF-A, 100 kN above a sleeper: the discretely supported infinite rail deflects 1.089 mm
// (docs/physics.md §10 case 3; reference computed with 81 supports, 4 digits). Our track is finite
// (61 sleepers, the load 18 m from either end, where the influence line has decayed as
// e^(-lambda x) ~ 3e-10) and cubic Hermite elements are exact for an EB beam loaded at nodes,
// so the only differences are the reference's rounding (0.05 %) and its own truncation:
// 0.2 % tolerance.
TEST(TrackStatics, RailDeflectionUnderWheelMatchesDiscreteSupportReference) {
  auto track =
      make_track(ref_a_track(61), nlohmann::json::array({single_wheel(1.0, 1e5, 0.0, 18.0)}));
  track->solve_static({});
  const double w = track->rail_deflection_at(18.0);
  EXPECT_NEAR(w, 1.089e-3, 0.002 * 1.089e-3);
  // Continuous-support (Winkler) closed form 1/(8 EI lambda^3) with k = K_s / d is 1.092 mm:
  // discreteness makes the real track 0.3 % stiffer above a sleeper.
  const double EI = 2.1e11 * 3.055e-5;
  const double ks = 1.0 / (1.0 / 2e8 + 1.0 / 4e7) / 0.6;  // N/m^2
  const double lambda = std::pow(ks / (4.0 * EI), 0.25);
  const double w_continuous = 1e5 / (8.0 * EI * lambda * lambda * lambda);
  EXPECT_NEAR(w_continuous, 1.092e-3, 0.0005e-3);  // the formula as docs/physics.md §8 states it
  EXPECT_LT(w, w_continuous);
  EXPECT_GT(w, 0.99 * w_continuous);
}

// Equilibrium: the footprints carry both rails' load, 2 x 100 kN (exact up to round-off).
TEST(TrackStatics, FootprintForcesCarryBothRails) {
  auto track =
      make_track(ref_a_track(41), nlohmann::json::array({single_wheel(750.0, 1e5, 0.0, 12.3)}));
  track->solve_static({});
  std::vector<double> f(track->interface_size());
  track->footprint_forces(f.data());
  double sum = 0.0;
  for (double x : f) sum += x;  // sleepers far away are lifted a little (negative lobes)
  EXPECT_NEAR(sum, 2e5, 1e-9 * 2e5);
  EXPECT_NEAR(track->contact_force(0), 1e5, 1e-9 * 1e5);
}

// Hertz: C_H for R_w = 0.46 m on R_r = 0.30 m steel is 9.41e10 N/m^1.5 and the static approach
// at 100 kN is 104 um (docs/physics.md §7, 3 digits): the static state must have exactly that
// wheel/rail approach (the table's rounding: 0.5 %).
TEST(TrackStatics, HertzApproachAtStaticLoad) {
  auto track =
      make_track(ref_a_track(41), nlohmann::json::array({single_wheel(750.0, 1e5, 0.0, 12.0)}));
  track->solve_static({});
  EXPECT_NEAR(track->hertz_constant(0), 9.41e10, 0.005 * 9.41e10);
  const double approach = track->vehicle_q()[0] - track->rail_deflection_at(12.0);
  EXPECT_NEAR(approach, 104e-6, 0.005 * 104e-6);
  EXPECT_NEAR(approach, std::pow(1e5 / track->hertz_constant(0), 2.0 / 3.0), 1e-12);
}

// A soil that settles uniformly by u under any load moves the whole track down by u and changes
// nothing else: the static iteration must converge to that state.
TEST(TrackStatics, IteratesWithTheSoilToConsistency) {
  auto track =
      make_track(ref_a_track(41), nlohmann::json::array({single_wheel(750.0, 1e5, 0.0, 12.0)}));
  track->solve_static({});
  const double w_fixed = track->rail_deflection_at(12.0);
  // Winkler soil of 1e8 N/m per footprint (whole sleeper).
  const int iterations =
      track->solve_static([](const std::vector<double>& f, std::vector<double>& u) {
        u.resize(f.size());
        for (std::size_t i = 0; i < f.size(); ++i) u[i] = f[i] / 1e8;
      });
  EXPECT_GT(iterations, 1);
  std::vector<double> f(track->interface_size());
  track->footprint_forces(f.data());
  for (std::size_t i = 0; i < f.size(); ++i)
    EXPECT_NEAR(track->footprint_u(i), f[i] / 1e8, 1e-9 * 1e-3);  // consistent to the tolerance
  EXPECT_GT(track->rail_deflection_at(12.0), w_fixed);            // the soil adds its settlement
}

}  // namespace
}  // namespace rumble
