// The vehicle/track micro-step allocates nothing (issue #3): after the first macro step, which
// factors the iteration matrix for its micro-step, advancing, reading the outputs and the
// save/restore of iterative couplers run on buffers sized at construction. Vehicles go through
// their plugins' C tables, so their allocations are counted too. Counted with
// tests/support/allocation_counter (a replaced malloc), in an executable of its own.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "track_fixture.hpp"

namespace rumble {
namespace {

/// Allocations while stepping `track` 20 macro steps of 1 ms with a moving footprint input.
long allocations_while_stepping(TrackParticipant& track) {
  const std::size_t n = track.interface_size();
  // Quadratic waveform, coefficient-major: coeff[k * 2n + i], u then v of each footprint.
  std::vector<double> motion(2 * n * 3, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    motion[i] = 1e-4;          // m, u at the start of the step
    motion[2 * n + i] = 1e-6;  // m, u's change over the step
    motion[n + i] = 1e-3;      // m/s, v
  }
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

TEST(TrackAllocation, TheCounterSeesAllocationsInPlugins) {
  // The tests above can fail: a plugin's create() (through its C table, nothing of the engine
  // in between) allocates the instance inside the dlopen'ed library, and the counter sees it.
  const ComponentType* type = testing::plugins().find(RUMBLE_KIND_VEHICLE, "single_wheel");
  ASSERT_NE(type, nullptr);
  const std::string params = R"({"mass": 750.0, "static_load": 92642.5})";
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  host.abi_minor = RUMBLE_ABI_MINOR;
  host.scenario_dir = ".";
  rumble_instance* instance = nullptr;
  const char* error = nullptr;
  long allocations = 0;
  {
    const testing::AllocationCounter counter;
    ASSERT_EQ(type->factory().create(params.c_str(), &host, &instance, &error), RUMBLE_OK)
        << (error != nullptr ? error : "");
    allocations = counter.count();
  }
  static_cast<const rumble_vehicle_api*>(type->factory().api)->common.destroy(instance);
  EXPECT_GE(allocations, 1);
}

}  // namespace
}  // namespace rumble
