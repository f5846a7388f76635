// rumble::coupling::GroupResiduals::measure_trial (SDK 1.1, appended for iterating couplers):
// the residual of an iterate relative to the group's run scale grown by the iterate for that call
// only, equal to what measure() gives once the same values are final, and never growing the
// scale itself. A host table with two output groups stands in for the engine.
#include <gtest/gtest.h>

#include <rumble/coupling.hpp>
#include <vector>

namespace {

using rumble::CosimHost;
using rumble::GroupResidual;
using rumble::coupling::GroupResiduals;

/// Participant 0 outputs "force" [N] x 2 then "gap" [m] x 1.
rumble_status groups(void*, std::uint32_t, std::uint32_t, rumble_channel_group* out,
                     std::uint64_t capacity, std::uint64_t* n) {
  static const rumble_channel_group kGroups[2] = {{"force", "N", 0, 2}, {"gap", "m", 2, 1}};
  *n = 2;
  for (std::uint64_t i = 0; i < capacity && i < 2; ++i) out[i] = kGroups[i];
  return RUMBLE_OK;
}

TEST(GroupResiduals, MeasureTrialDoesNotGrowTheScale) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.channel_groups = &groups;
  const CosimHost host(&table);
  GroupResiduals residuals(host, 0);
  residuals.observe({1.0, -4.0, 0.5});  // scales: force 4 N, gap 0.5 m
  std::vector<GroupResidual> out(2);
  const std::vector<double> used{1.0, -3.0, 0.5}, produced{1.0, -5.0, 0.25};
  residuals.measure_trial(used, 0, produced, out.data());
  EXPECT_EQ(out[0].group, "force");
  EXPECT_DOUBLE_EQ(out[0].absolute, 2.0);
  EXPECT_DOUBLE_EQ(out[0].relative, 0.4);  // the iterate's 5 N counts in this call
  EXPECT_DOUBLE_EQ(out[1].absolute, 0.25);
  EXPECT_DOUBLE_EQ(out[1].relative, 0.5);
  residuals.measure_trial(used, 0, {1.0, -4.0, 0.5}, out.data());
  EXPECT_DOUBLE_EQ(out[0].relative, 0.25);  // 1 N of 4 N: the 5 N iterate left no trace
  // Final: measure() gives the trial's numbers and grows the scale.
  std::vector<GroupResidual> final_out(2);
  residuals.measure_trial(used, 0, produced, out.data());
  residuals.measure(used, 0, produced, final_out.data());
  for (std::size_t g = 0; g < 2; ++g) {
    EXPECT_EQ(final_out[g].absolute, out[g].absolute);
    EXPECT_EQ(final_out[g].relative, out[g].relative);
  }
  residuals.measure_trial(used, 0, {1.0, -4.0, 0.5}, out.data());
  EXPECT_DOUBLE_EQ(out[0].relative, 0.2);  // 1 N of 5 N now
}

TEST(GroupResiduals, MeasureTrialEvaluatesTheWaveformAtTheEndOfTheStep) {
  rumble_cosim_host table{};
  table.struct_size = sizeof table;
  table.channel_groups = &groups;
  const CosimHost host(&table);
  const GroupResiduals residuals(host, 0);
  // order 1: value at tau = 1 is c0 + c1 (three channels: coefficients c0 then c1).
  const std::vector<double> wave{1.0, 2.0, 0.0, 1.0, -1.0, 0.5};
  std::vector<GroupResidual> out(2);
  residuals.measure_trial(wave, 1, {2.0, 1.0, 0.5}, out.data());
  EXPECT_DOUBLE_EQ(out[0].absolute, 0.0);
  EXPECT_DOUBLE_EQ(out[1].absolute, 0.0);
  EXPECT_DOUBLE_EQ(out[1].relative, 0.0);
}

}  // namespace
