// The vehicle/track micro-step allocates nothing (issue #3): after the first macro step, which
// factors the iteration matrix for its micro-step, advancing, reading the outputs and the
// save/restore of iterative couplers run on buffers sized at construction. Vehicles go through
// their plugins' C tables, so their allocations are counted too. Counted with
// tests/support/allocation_counter (a replaced malloc), in an executable of its own.
#include <gtest/gtest.h>

#include <vector>

#include "allocation_counter.hpp"
#include "track_fixture.hpp"

namespace rumble {
namespace {

/// Allocations while stepping `track` 20 macro steps of 1 ms with a moving footprint input.
long allocations_while_stepping(TrackParticipant& track) {
  const std::size_t n = track.interface_size();
  std::vector<double> motion(2 * n * 3, 0.0);  // quadratic waveform: u and v of each footprint
  for (std::size_t i = 0; i < n; ++i) motion[i] = 1e-4;  // m, constant term of u
  const rumble_waveform input{2, 2 * n, motion.data()};
  std::vector<double> forces(n), state(track.state_size());
  track.set_input(input);
  track.advance(0.0, 1e-3);  // factors the dynamic matrix for this micro-step
  const testing::AllocationCounter counter;
  for (int k = 1; k <= 20; ++k) {
    track.set_input(input);
    track.save_state(state.data());
    track.advance(k * 1e-3, 1e-3);
    if (k == 10) {  // an iterative coupler's repeat of a macro step
      track.restore_state(state.data());
      track.advance(k * 1e-3, 1e-3);
    }
    track.footprint_forces(forces.data());
  }
  EXPECT_GT(track.contact_force(0), 0.0);
  return counter.count();
}

TEST(TrackAllocation, SingleWheelOnRandomUnevenness) {
  nlohmann::json t = testing::ref_a_track(40);
  t["unevenness"] = {{"type", "random"},
                     {"class", "FRA4"},
                     {"seed", 7},
                     {"wavelength_min", 0.5},
                     {"wavelength_max", 20.0}};
  auto track =
      testing::make_track(t, nlohmann::json::array({testing::single_wheel(750.0, 1e5, 30.0, 6.0)}));
  track->solve_static({});
  EXPECT_EQ(allocations_while_stepping(*track), 0);
}

TEST(TrackAllocation, MultibodyHalfTrain) {
  const nlohmann::json train = {{"type", "mbs"},
                                {"params", {{"file", "scenarios/vehicles/half_train.json"}}},
                                {"speed", 30.0},
                                {"start", 24.0}};
  auto track = testing::make_track(testing::ref_a_track(60), nlohmann::json::array({train}));
  track->solve_static({});
  EXPECT_EQ(allocations_while_stepping(*track), 0);
}

TEST(TrackAllocation, TheCounterCounts) {
  // The tests above can fail: an allocation in the counted window is seen.
  const testing::AllocationCounter counter;
  const std::vector<double> v(100);
  EXPECT_GE(counter.count(), 1);
}

}  // namespace
}  // namespace rumble
