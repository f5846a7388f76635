// A wheel preloaded by P0 on a rigid rail makes small oscillations at (1/2 pi) sqrt(k_H / M),
// k_H = 1.5 C_H^(2/3) P0^(1/3): 220 Hz for M = 750 kg, P0 = 100 kN (docs/physics.md §10 case 6).
// And the wheel never pulls on the rail: a large bump makes it lose contact with F = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "track/hertz.hpp"
#include "track_fixture.hpp"

namespace rumble {
namespace {

using testing::make_track;
using testing::single_wheel;

nlohmann::json rigid_track() {
  // Pads and ballast 1e13 N/m: the support under the wheel is 7000x stiffer than the contact.
  nlohmann::json t = testing::ref_a_track(21);
  t["railpad"] = {{"k", 1e13}, {"c", 0.0}};
  t["ballast"] = {{"k", 1e13}, {"c", 0.0}};
  return t;
}

TEST(HertzContact, SmallOscillationFrequencyOfPreloadedWheel) {
  auto track =
      make_track(rigid_track(), nlohmann::json::array({single_wheel(750.0, 1e5, 0.0, 6.0)}));
  track->solve_static({});
  // Kick the wheel: 1 mm/s gives an amplitude of 0.7 um against a static approach of 104 um,
  // so the Hertz non-linearity shifts the frequency by < 1e-4.
  std::vector<double> state(track->state_size());
  track->save_state(state.data());
  const std::size_t nt = static_cast<std::size_t>(track->track_x().size());
  const std::size_t qd_index = 1 + 3 * nt + 1;  // layout: t, x, v, a, q, qd, ...
  state[qd_index] = 1e-3;
  track->restore_state(state.data());

  const double H = 1e-5, P0 = 1e5;
  double previous = track->contact_force(0) - P0, t_prev = 0.0;
  std::vector<double> upward_crossings;
  for (int k = 0; k < 5000; ++k) {
    track->advance(k * H, H);
    const double now = track->contact_force(0) - P0;
    if (previous < 0.0 && now >= 0.0)
      upward_crossings.push_back(t_prev + H * previous / (previous - now));
    previous = now;
    t_prev = (k + 1) * H;
  }
  ASSERT_GE(upward_crossings.size(), 8u);
  const double period =
      (upward_crossings.back() - upward_crossings.front()) / (upward_crossings.size() - 1);
  const double k_h = linearized_stiffness(track->hertz_constant(0), P0);
  const double expected = std::sqrt(k_h / 750.0) / (2.0 * std::numbers::pi);
  EXPECT_NEAR(expected, 220.0, 1.5);  // docs/physics.md §7's rounded value [Hz]
  // Newmark's period error (omega h)^2 / 12 ~ 2e-5 at h = 1e-5 s; support compliance 1.4e-4:
  // 0.1 % is an honest bound.
  EXPECT_NEAR(1.0 / period, expected, 0.001 * expected);
}

TEST(HertzContact, LosesContactOverABumpWithoutTension) {
  nlohmann::json t = testing::ref_a_track(41);
  // A 2 mm bump 0.2 m long at 30 m/s throws a 750 kg wheel carrying only 10 kN off the rail.
  t["unevenness"] = {{"type", "bump"}, {"position", 12.0}, {"length", 0.2}, {"height", 2e-3}};
  auto track = make_track(t, nlohmann::json::array({single_wheel(750.0, 1e4, 30.0, 9.0)}));
  track->solve_static({});
  double min_force = 1e300;
  int steps_without_contact = 0;
  for (int k = 0; k < 300; ++k) {  // 0.3 s: to x = 18 m
    track->advance(k * 1e-3, 1e-3);
    min_force = std::min(min_force, track->contact_force(0));
    if (track->contact_force(0) == 0.0) ++steps_without_contact;
  }
  EXPECT_EQ(min_force, 0.0);
  EXPECT_GT(steps_without_contact, 0);
}

}  // namespace
}  // namespace rumble
