// What a soil participant takes (docs/couplers.md, "The coupler contract"): until a coupler sets
// its input, the static footprint forces its statics were solved under, held, so that a soil
// advanced with nothing set stays where its statics put it; and the force recorded as the one it
// took (footprint_force.csv, interface.csv) is the waveform of its last advance at tau = 1,
// whatever the coupler set since. picky_soil: c u' + k u = F per footprint.
#include <gtest/gtest.h>

#include "boundary_support.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "run/participant.hpp"

namespace rumble::testing {
namespace {

TEST(SoilInput, StartsAtTheStaticForcesAndRecordsWhatTheLastStepTook) {
  PluginRegistry registry;
  registry.load_library(fixture_plugin("boundary_fixtures"));
  SoilInstance soil(*registry.find(RUMBLE_KIND_SOIL, "picky_soil"), "/soil",
                    {{"k", 1e8},
                     {"c", 2e5},
                     {"sub_step", 1e-4},
                     {"max_step", 1.0},
                     {"stall_at", 1e30},
                     {"csc_defect", "none"}},
                    ".");
  soil.accept_layout({{0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}});
  const std::vector<double> statics{1e4, 2e4};  // N
  std::vector<double> u;
  soil.initialize(0.0, statics, u);
  SoilSide side("soil", soil, statics);
  std::vector<double> before(4), after(4), taken(2);
  side.applied_force(taken.data());
  EXPECT_EQ(taken, statics) << "before the first step: the static forces";
  side.get_output(before.data());
  side.advance(0.0, 1e-3);  // nothing set: the static forces, held
  side.get_output(after.data());
  EXPECT_DOUBLE_EQ(after[0], before[0]);
  EXPECT_DOUBLE_EQ(after[1], before[1]);
  EXPECT_EQ(after[2], 0.0);  // at rest
  // A linear waveform: what the step took at its end, 3e4 + 1e3 and 4e4 - 2e3 N ...
  std::vector<double> coeff{3e4, 4e4, 1e3, -2e3};
  side.set_input({1, 2, coeff.data()});
  side.advance(1e-3, 1e-3);
  side.applied_force(taken.data());
  EXPECT_EQ(taken, (std::vector<double>{3.1e4, 3.8e4}));
  // ... which the next step's input, set before the step is reported, does not change.
  std::vector<double> next{9e4, 9e4};
  side.set_input({0, 2, next.data()});
  side.applied_force(taken.data());
  EXPECT_EQ(taken, (std::vector<double>{3.1e4, 3.8e4}));
}

}  // namespace
}  // namespace rumble::testing
