// RunResiduals: a run's interface residual per channel group relative to the group's scale over
// the whole run, from the per-step reports (absolute, and relative to the scale so far).
#include "run/run_residuals.hpp"

#include <gtest/gtest.h>

namespace rumble {
namespace {

rumble_group_residual report(const char* group, double absolute, double scale_so_far) {
  return {group, absolute, scale_so_far > 0.0 ? absolute / scale_so_far : absolute};
}

// A group at rest before the run (a footprint velocity): its first moving step reads 1 against
// the scale so far; against the run's scale the largest residual is a tenth.
TEST(RunResiduals, AGroupStartingAtRestIsMeasuredAgainstTheRunsScale) {
  RunResiduals r;
  r.add(report("footprint_velocity", 1e-3, 1e-3));  // first step: v = 1 mm/s, used 0: reads 1
  r.add(report("footprint_velocity", 5e-4, 1e-2));
  r.add(report("footprint_velocity", 2e-4, 1e-2));
  EXPECT_DOUBLE_EQ(r.relative().at("footprint_velocity"), 1e-3 / 1e-2);
  EXPECT_DOUBLE_EQ(r.absolute().at("footprint_velocity"), 1e-3);
  EXPECT_DOUBLE_EQ(r.largest_relative(), 0.1);
}

// Groups are kept apart, and the largest relative one is the run's.
TEST(RunResiduals, GroupsAreKeptApart) {
  RunResiduals r;
  r.add(report("footprint_displacement", 1e-6, 1e-3));
  r.add(report("footprint_force", 2e3, 5e4));
  EXPECT_DOUBLE_EQ(r.relative().at("footprint_displacement"), 1e-3);
  EXPECT_DOUBLE_EQ(r.relative().at("footprint_force"), 0.04);
  EXPECT_DOUBLE_EQ(r.largest_relative(), 0.04);
}

// A report whose group is still all zeros (relative = absolute, the SDK's fallback) tells no
// scale; a group that never shows one keeps the per-step value.
TEST(RunResiduals, AGroupWithoutAScaleKeepsItsPerStepValue) {
  RunResiduals r;
  r.add(report("footprint_velocity", 0.2, 0.0));
  EXPECT_DOUBLE_EQ(r.relative().at("footprint_velocity"), 0.2);
  r.add(report("footprint_velocity", 0.1, 2.0));
  EXPECT_DOUBLE_EQ(r.relative().at("footprint_velocity"), 0.2 / 2.0);
}

TEST(RunResiduals, NoReportsNoResidual) {
  const RunResiduals r;
  EXPECT_TRUE(r.relative().empty());
  EXPECT_EQ(r.largest_relative(), 0.0);
}

}  // namespace
}  // namespace rumble
