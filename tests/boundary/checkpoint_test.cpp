// Checkpoints of a participant (ABI 1.1): RUMBLE_CHECKPOINT_SLOTS slots, restorable any number of
// times, freeable; a plugin that declares own checkpoints keeps them itself. picky_soil does.
#include <gtest/gtest.h>

#include "boundary_support.hpp"
#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "run/participant.hpp"

namespace rumble::testing {
namespace {

TEST(Checkpoints, PluginHeldSlotsRestoreExactlyAndCanBeFreed) {
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
  ASSERT_TRUE(soil.keeps_checkpoints());
  soil.accept_layout({{0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}});
  std::vector<double> u;
  soil.initialize(0.0, {1e4, 2e4}, u);
  SoilSide side("soil", soil, {1e4, 2e4});
  std::vector<double> coeff{5e4, 5e4}, before(4), after(4), again(4);
  side.set_input({0, 2, coeff.data()});
  side.checkpoint(3);
  side.get_output(before.data());
  side.advance(0.0, 1e-3);
  side.get_output(after.data());
  EXPECT_NE(after, before);
  for (int k = 0; k < 2; ++k) {  // a slot restores as often as asked
    side.rollback(3);
    side.get_output(again.data());
    EXPECT_EQ(again, before);
    side.advance(0.0, 1e-3);
    side.get_output(again.data());
    EXPECT_EQ(again, after);  // bit-identical repeat
  }
  side.free_checkpoint(3);
  EXPECT_THROW(side.rollback(3), RunError);
  try {
    side.checkpoint(RUMBLE_CHECKPOINT_SLOTS);
    FAIL() << "slot beyond the last accepted";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(), "checkpoint slot 4 does not exist (slots 0..3)");
  }
}

}  // namespace
}  // namespace rumble::testing
