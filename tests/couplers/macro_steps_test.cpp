// rumble::coupling::MacroSteps (rumble/macro_steps.hpp) and CutEnergy (rumble/cut_energy.hpp),
// the SDK 1.2 pieces of an adaptive macro step, without an engine:
//   - fixed steps are exactly the SDK 1.1 ones (index-computed starts, a short last step);
//   - the controller grows the step by max_change while the error is 0, shrinks it while the
//     error is large, keeps every step a whole number of min_step within the bounds, ends
//     exactly at t_end, and settles where the error model puts it for an error of order p + 1
//     in h, p = 0 and 1;
//   - a step above the tolerance is taken again, shorter;
//   - bounds given to accept() cut a growth or a shrink to whole min_steps within them, and the
//     step moves on from there; StepChangeLimit's bounds are the lag L -+ tau share allowed /
//     |v| by hand, L relaxing towards the step over tau, unlimited while still or without tau;
//   - inverted bounds are refused with both values and the fix;
//   - the energy residual of a step is the trapezoid of the power residual (the force side's
//     forces on the velocities it was given minus the motion side's given forces on its
//     velocities), by hand on two footprints; undo() forgets a step.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <rumble/cut_energy.hpp>
#include <rumble/macro_steps.hpp>
#include <vector>

namespace {

using rumble::CosimHost;
using rumble::coupling::AdaptiveStep;
using rumble::coupling::CutEnergy;
using rumble::coupling::MacroSteps;
using rumble::coupling::StepChangeLimit;
using ::testing::HasSubstr;

/// The adaptive step with its schema's defaults and these bounds [s].
AdaptiveStep adaptive(double min_step, double max_step) {
  const std::string params = R"({"adaptive": {"min_step": )" + std::to_string(min_step) +
                             R"(, "max_step": )" + std::to_string(max_step) + "}}";
  return rumble::coupling::read_adaptive_step(rumble::Params(params));
}

/// True when h is a whole number of q (to round-off).
bool whole_multiple(double h, double q) {
  return std::abs(h / q - std::round(h / q)) < 1e-9;
}

TEST(MacroSteps, FixedStepsAreTheIndexedOnes) {
  MacroSteps steps(0.0, 0.0105, 1e-3, AdaptiveStep{});
  std::size_t k = 0;
  for (; !steps.done(); ++k) {
    EXPECT_EQ(steps.t(), rumble::coupling::macro_step_start(0.0, 1e-3, k));
    EXPECT_EQ(steps.h(), rumble::coupling::macro_step_length(0.0, 0.0105, 1e-3, k));
    steps.accept(123.0, 0);  // errors do not steer fixed steps
  }
  EXPECT_EQ(k, 11u);
  EXPECT_EQ(steps.error(), 0.0);
}

TEST(MacroSteps, AnErrorFreeRunGrowsToTheLongestStepAndEndsOnTime) {
  const double q = 1e-4, t_end = 0.05;
  MacroSteps steps(0.0, t_end, 1e-4, adaptive(q, 2e-3));
  double previous = 0.0, before_last = 0.0, end = 0.0;
  while (!steps.done()) {
    const double h = steps.h();
    EXPECT_GE(h, q * (1.0 - 1e-12));
    EXPECT_LE(h, 2e-3 * (1.0 + 1e-12));
    if (steps.t() + h < t_end - 1e-12) {
      EXPECT_TRUE(whole_multiple(h, q)) << h;
      // No error: the step only grows, until the time left is taken in equal steps of at most
      // the longest ...
      const double left = t_end - steps.t();
      EXPECT_GE(h, std::min(previous, left / std::ceil(left / 2e-3 - 1e-9)) - 1e-12);
      EXPECT_LE(h, 1.5 * previous + q) << "by at most max_change (1.5) and rounding";
    }
    before_last = previous;
    previous = h;
    end = steps.t() + h;
    steps.accept(0.0, 0);
  }
  // ... so that the run does not end on a short remainder (docs/couplers.md, adaptive steps).
  EXPECT_GE(previous, before_last - q - 1e-12);
  EXPECT_DOUBLE_EQ(end, t_end);
  EXPECT_DOUBLE_EQ(steps.t(), t_end);
}

TEST(MacroSteps, ALargeErrorShrinksTheStepToTheShortest) {
  MacroSteps steps(0.0, 1.0, 2e-3, adaptive(1e-4, 2e-3));
  for (int k = 0; k < 30; ++k) steps.accept(1e6, 0);  // error >> 1: every change 0.2
  EXPECT_DOUBLE_EQ(steps.h(), 1e-4);
  EXPECT_GT(steps.error(), 1.0);
}

TEST(MacroSteps, SettlesWhereTheErrorModelPutsIt) {
  // A residual c h^(p + 1) (extrapolation of order p) is on the tolerance at
  // h* = (tolerance / c)^(1 / (p + 1)). Each step sets h_next = safety h e^(-1 / (p + 1)) =
  // safety h*: the controller lands there in one step and stays, its error safety^(p + 1).
  for (const std::uint32_t p : {0u, 1u}) {
    const AdaptiveStep a = adaptive(1e-6, 1e-2);
    const double c = p == 0 ? 10.0 : 1e5;  // 1/s or 1/s^2
    const double target = a.safety * std::pow(a.tolerance / c, 1.0 / (p + 1.0));
    MacroSteps steps(0.0, 0.5, 1e-3, a);
    for (int k = 0; k < 50 && !steps.done(); ++k) {
      const double h = steps.h();
      steps.accept(c * std::pow(h, p + 1.0) / a.tolerance, p);
    }
    EXPECT_NEAR(steps.h() / target, 1.0, 0.02) << p;  // min_step rounding: 1e-6 of 9e-4, 2.8e-4
    EXPECT_NEAR(steps.error(), std::pow(a.safety, p + 1.0), 0.02) << p;
  }
}

TEST(MacroSteps, AStepAboveTheToleranceIsTakenAgainShorter) {
  const AdaptiveStep a = adaptive(1e-4, 2e-3);
  MacroSteps steps(0.0, 1.0, 1e-3, a);
  EXPECT_FALSE(steps.retake(0.5, 1));
  EXPECT_DOUBLE_EQ(steps.h(), 1e-3);
  // 8 times the tolerance at second order: h 0.9 / sqrt(8) = 0.32 ms, rounded to 0.3 ms.
  EXPECT_TRUE(steps.retake(8.0, 1));
  EXPECT_NEAR(steps.h(), 3e-4, 1e-15);
  EXPECT_EQ(steps.retaken(), 1u);
  EXPECT_EQ(steps.taken(), 0u);
}

TEST(MacroSteps, BoundsCutAChangeToWholeMinStepsWithinThem) {
  const AdaptiveStep a = adaptive(1e-4, 2e-3);
  // Error 0: the step would grow by max_change (1.5), from 1 ms to 1.5 ms; within 1.23 ms it
  // grows to 1.2 ms, and on from there once unbounded.
  MacroSteps grow(0.0, 1.0, 1e-3, a);
  grow.accept(0.0, 0, 0.0, 1.23e-3);
  EXPECT_NEAR(grow.h(), 1.2e-3, 1e-15);
  grow.accept(0.0, 0);
  EXPECT_NEAR(grow.h(), 1.8e-3, 1e-15);
  // Bounds below the step hold it rather than shrink it.
  MacroSteps hold(0.0, 1.0, 1e-3, a);
  hold.accept(0.0, 0, 0.0, 0.5e-3);
  EXPECT_NEAR(hold.h(), 1e-3, 1e-15);
  // Error 3 at first order: 0.9 / 3 = 0.3 ms; no shorter than 0.62 ms, it is 0.7 ms.
  MacroSteps shrink(0.0, 1.0, 1e-3, a);
  shrink.accept(3.0, 0, 0.62e-3, 2e-3);
  EXPECT_NEAR(shrink.h(), 0.7e-3, 1e-15);
  // Unbounded, the same as accept(error, order).
  MacroSteps free(0.0, 1.0, 1e-3, a), plain(0.0, 1.0, 1e-3, a);
  free.accept(3.0, 0, -1e300, 1e300);
  plain.accept(3.0, 0);
  EXPECT_EQ(free.h(), plain.h());
}

// A soil that outputs displacements and velocities of two footprints (the test's cut_groups).
rumble_status cut_groups(void*, std::uint32_t p, std::uint32_t side, rumble_channel_group* out,
                         std::uint64_t capacity, std::uint64_t* n);

TEST(StepChangeLimit, IsTheLagWithinAShareOfTheVelocitysAllowedErrorOverItsSpeed) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.channel_groups = &cut_groups;
  const CosimHost host(&table);
  AdaptiveStep a = adaptive(1e-4, 2e-3);
  const double tau = a.relaxation_time, share = StepChangeLimit::kChangeShare;
  const double floor = a.absolute.at("footprint_velocity");  // 1e-3 m/s
  a.tolerance = 0.05;
  StepChangeLimit limit(host, 1, a);
  // At rest: unlimited.
  limit.observe({0.0, 0.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(limit.longest(), std::numeric_limits<double>::infinity());
  // After a step of 1 ms the lag is 1 ms; moving at 0.04 m/s at most (scale 0.04 m/s: the
  // allowed error 0.05 x 0.04 = 2e-3 m/s, above the floor): 1 ms -+ tau share 2e-3 / 0.04.
  limit.observe({1e-4, 2e-4, -0.04, 0.01}, 1e-3);
  const double reach = tau * share * 2e-3 / 0.04;
  EXPECT_NEAR(limit.longest(), 1e-3 + reach, 1e-15);
  EXPECT_NEAR(limit.shortest(), 1e-3 - reach, 1e-15);
  // Slower (0.01 m/s), the scale stays 0.04 m/s: the reach is 4 times as long. After a step of
  // 0.5 ms the lag has relaxed part of the way: 0.5 ms + 0.5 ms exp(-0.5 ms / tau).
  limit.observe({1e-4, 2e-4, 0.01, 0.0}, 0.5e-3);
  const double lag = 0.5e-3 + 0.5e-3 * std::exp(-0.5e-3 / tau);
  EXPECT_NEAR(limit.longest(), lag + 4.0 * reach, 1e-15);
  // Below the floor's share the floor holds: a scale of 1e-3 m/s allows 5e-5 < 1e-3 m/s.
  StepChangeLimit slow(host, 1, a);
  slow.observe({0.0, 0.0, 1e-3, 0.0}, 1e-3);
  EXPECT_NEAR(slow.longest(), 1e-3 + tau * share * floor / 1e-3, 1e-15);
  // No relaxation time (a hand-made AdaptiveStep) or fixed steps: unlimited.
  a.relaxation_time = 0.0;
  StepChangeLimit none(host, 1, a);
  none.observe({1e-4, 2e-4, -0.04, 0.01}, 1e-3);
  EXPECT_EQ(none.longest(), std::numeric_limits<double>::infinity());
  StepChangeLimit fixed(host, 1, AdaptiveStep{});
  fixed.observe({1e-4, 2e-4, -0.04, 0.01}, 1e-3);
  EXPECT_EQ(fixed.shortest(), -std::numeric_limits<double>::infinity());
}

TEST(MacroSteps, TheStepErrorIsEachGroupsResidualOnItsScaleWithAFloor) {
  const AdaptiveStep a = adaptive(1e-4, 1e-3);
  const double tolerance = a.tolerance, floor = a.absolute.at("footprint_velocity");
  // The displacement on its scale: 0.5 of the tolerance. The velocity from rest (no scale yet):
  // against its floor alone, 3 times it.
  const rumble::GroupResidual r[2] = {{"footprint_displacement", 0.5 * tolerance * 1e-3, 0.0, 1e-3},
                                      {"footprint_velocity", 3.0 * floor, 1.0, 0.0}};
  EXPECT_DOUBLE_EQ(rumble::coupling::step_error(a, r, 1), 0.5);
  EXPECT_DOUBLE_EQ(rumble::coupling::step_error(a, r, 2), 3.0);
}

TEST(MacroSteps, InvertedBoundsAreRefusedWithBothValues) {
  const rumble::Params params(R"({"adaptive": {"min_step": 0.001, "max_step": 0.0001}})");
  try {
    rumble::coupling::read_adaptive_step(params);
    FAIL() << "inverted bounds accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("params/adaptive: min_step 0.001 s is longer than max_step "
                                    "0.0001 s; give min_step <= max_step"));
  }
  EXPECT_FALSE(rumble::coupling::read_adaptive_step(rumble::Params("{}")).enabled());
}

TEST(MacroSteps, DefaultsComeFromTheSchemaAlone) {
  // Declared once: the values read without a host to fill them are the schema's defaults.
  const nlohmann::json schema = nlohmann::json::parse(rumble::coupling::kAdaptiveStepObjectSchema);
  const AdaptiveStep a = adaptive(1e-4, 1e-3);
  const nlohmann::json& p = schema.at("properties");
  EXPECT_EQ(a.tolerance, p.at("tolerance").at("default").get<double>());
  EXPECT_EQ(a.safety, p.at("safety").at("default").get<double>());
  const nlohmann::json& floors = p.at("absolute_tolerance").at("properties");
  EXPECT_EQ(a.absolute.size(), floors.size());
  for (const auto& [group, floor] : a.absolute)
    EXPECT_EQ(floor, floors.at(group).at("default").get<double>()) << group;
  EXPECT_EQ(a.retake, p.at("retake").at("default").get<bool>());
  EXPECT_EQ(a.relaxation_time, p.at("relaxation_time").at("default").get<double>());
  EXPECT_DOUBLE_EQ(a.min_step, 1e-4);
}

// A host with two footprints: participant 0 (track) outputs "footprint_force" [N] and takes
// "footprint_displacement" [m] and "footprint_velocity" [m/s]; participant 1 (soil) outputs
// displacement then velocity and takes the force.
rumble_status cut_groups(void*, std::uint32_t p, std::uint32_t side, rumble_channel_group* out,
                         std::uint64_t capacity, std::uint64_t* n) {
  static const rumble_channel_group kForce[1] = {{"footprint_force", "N", 0, 2}};
  static const rumble_channel_group kMotion[2] = {{"footprint_displacement", "m", 0, 2},
                                                  {"footprint_velocity", "m/s", 2, 2}};
  const bool force = (p == 0) == (side == RUMBLE_SIDE_OUTPUT);
  *n = force ? 1 : 2;
  for (std::uint64_t i = 0; i < capacity && i < *n; ++i) out[i] = force ? kForce[i] : kMotion[i];
  return RUMBLE_OK;
}

TEST(CutEnergy, IsThePowerResidualOfEachSidesOwnViewOverTheStep) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.channel_groups = &cut_groups;
  const CosimHost host(&table);
  CutEnergy energy(host, 0, 1);
  // At the start both sides see 100 N x 0.01 m/s + 200 N x 0.02 m/s = 5 W.
  energy.start({100.0, 200.0}, {1e-3, 2e-3, 0.01, 0.02});
  // Over 1 ms the track was given a linear velocity waveform (order 1) ending at (0.02, 0.01)
  // m/s and put out (300, 100) N: 7 W. The soil was given (310, 90) N held (order 0) and ended
  // at (0.03, 0) m/s: 9.3 W.
  const std::vector<double> track_in{1e-3, 2e-3, 0.01, 0.02, 0.0, 0.0, 0.01, -0.01};
  const std::vector<double> soil_in{310.0, 90.0};
  const std::vector<double> track_out{300.0, 100.0}, soil_out{1.1e-3, 2e-3, 0.03, 0.0};
  const double residual = energy.step(1e-3, track_in, 1, track_out, soil_in, 0, soil_out);
  EXPECT_NEAR(residual, 0.5e-3 * ((5.0 - 5.0) + (7.0 - 9.3)), 1e-15);
  EXPECT_NEAR(energy.work(), 0.5e-3 * (5.0 + 9.3), 1e-15);
  // Forgotten and taken again: the same numbers (the start is restored).
  energy.undo();
  EXPECT_NEAR(energy.step(1e-3, track_in, 1, track_out, soil_in, 0, soil_out), residual, 1e-18);
  // The next step starts from this one's end (-2.3 W); given the soil's velocities, the track
  // puts 300 N x 0.03 m/s = 9 W through against the soil's 9.3 W: -0.3 W.
  EXPECT_NEAR(energy.step(2e-3, {0, 0, 0.03, 0.0}, 0, track_out, soil_in, 0, soil_out),
              0.5 * 2e-3 * (-2.3 - 0.3), 1e-15);
}

TEST(CutEnergy, NamesAMissingGroup) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.channel_groups = &cut_groups;
  table.participant_name = [](void*, std::uint32_t p) -> const char* {
    return p == 0 ? "track" : "soil";
  };
  const CosimHost host(&table);
  try {
    CutEnergy energy(host, 0, 1, "footprint_force", "rail_velocity");
    FAIL() << "a missing group accepted";
  } catch (const CosimHost::Stop& e) {
    EXPECT_THAT(e.what(), HasSubstr("needs the output group 'rail_velocity' of participant "
                                    "'soil', which it does not have"));
  }
}

}  // namespace
