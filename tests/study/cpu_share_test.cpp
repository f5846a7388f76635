// How a study splits the CPUs it may use among the runs it has going at once
// (core/cpu_affinity.hpp): disjoint shares covering every CPU when there are enough, single
// shared CPUs when there are not.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/cpu_affinity.hpp"

namespace rumble {
namespace {

TEST(CpuShare, SplitsTheCpusIntoDisjointSharesThatCoverThemAll) {
  const std::vector<int> cpus = {0, 1, 2, 3, 8, 9};
  EXPECT_EQ(cpu_share(cpus, 0, 2), (std::vector<int>{0, 2, 8}));
  EXPECT_EQ(cpu_share(cpus, 1, 2), (std::vector<int>{1, 3, 9}));
  EXPECT_EQ(cpu_share(cpus, 2, 4), (std::vector<int>{2}));
  EXPECT_EQ(cpu_share(cpus, 0, 4), (std::vector<int>{0, 8}));
  std::vector<int> all;
  for (int k = 0; k < 4; ++k) {
    const auto share = cpu_share(cpus, k, 4);
    all.insert(all.end(), share.begin(), share.end());
  }
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, cpus);
  EXPECT_EQ(cpu_share(cpus, 0, 1), cpus);
}

TEST(CpuShare, MoreRunsThanCpusShareSingleCpus) {
  const std::vector<int> cpus = {4, 5};
  EXPECT_EQ(cpu_share(cpus, 0, 3), (std::vector<int>{4}));
  EXPECT_EQ(cpu_share(cpus, 1, 3), (std::vector<int>{5}));
  EXPECT_EQ(cpu_share(cpus, 2, 3), (std::vector<int>{4}));
}

TEST(CpuShare, ThisProcessSeesAtLeastOneCpu) {
  const std::vector<int> cpus = usable_cpu_list();
  ASSERT_FALSE(cpus.empty());
  EXPECT_EQ(usable_cpus(), static_cast<int>(cpus.size()));
  EXPECT_TRUE(std::is_sorted(cpus.begin(), cpus.end()));
}

}  // namespace
}  // namespace rumble
