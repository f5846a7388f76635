// Energy balance of an undamped vehicle/track run: a wheel at rest on the REF-A track with all
// damping removed, kicked, then left alone. Kinetic + strain + Hertz potential - work of the
// constant wheel load stays constant; Newmark's average acceleration rule conserves it exactly
// for the linear part and to O(h^2) through the non-linear contact.
#include <gtest/gtest.h>

#include <cmath>

#include "track_fixture.hpp"

namespace rumble {
namespace {

double total_energy(TrackParticipant& track, double load) {
  return track.track_energy() + track.vehicle_kinetic_energy() + track.contact_energy() -
         load * track.vehicle_q()[0];
}

double energy_drift(double micro_step) {
  nlohmann::json t = testing::ref_a_track(41);
  t["railpad"]["c"] = 0.0;
  t["ballast"]["c"] = 0.0;
  t["integrator"] = {{"micro_step", micro_step}};
  auto track =
      testing::make_track(t, nlohmann::json::array({testing::single_wheel(750.0, 1e5, 0.0, 12.0)}));
  track->solve_static({});
  std::vector<double> state(track->state_size());
  track->save_state(state.data());
  const std::size_t nt = static_cast<std::size_t>(track->track_x().size());
  state[1 + 3 * nt + 1] = 0.05;  // wheel velocity 5 cm/s: kinetic energy 0.94 J
  track->restore_state(state.data());
  const double e0 = total_energy(*track, 1e5);
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {  // 0.02 s, several P2 and pad periods
    track->advance(k * 1e-4, 1e-4);
    worst = std::max(worst, std::abs(total_energy(*track, 1e5) - e0));
  }
  return worst / (0.5 * 750.0 * 0.05 * 0.05);  // relative to the energy put in
}

TEST(TrackEnergy, UndampedRunConservesEnergy) {
  const double coarse = energy_drift(2e-5);
  const double fine = energy_drift(1e-5);
  EXPECT_LT(coarse, 1e-3);  // 0.1 % of the energy put in
  // Second order: halving h divides the drift by about 4 (>= 2.5 allows for round-off).
  EXPECT_GT(coarse / std::max(fine, 1e-15), 2.5);
}

}  // namespace
}  // namespace rumble
