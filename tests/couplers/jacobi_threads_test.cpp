// Jacobi on two threads gives the results of Jacobi on one, to the bit (docs/couplers.md, "What
// the couplers cost"): the two threads change when each side's work is done, never what it
// computes. On the small FEM scenario, where on one thread the host gives the soil every core
// after its first steps (the sides then never advance at once, run/core_share.hpp) and the soil
// changes its team size, and the soil's checkpoint of every step is taken on the worker thread;
// and on the small Winkler scenario with a rail dip and an adaptive step (steps taken again:
// both sides restored).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "coupler_runs.hpp"

namespace rumble::testing {
namespace {

/// Every CSV file of the two results directories, byte for byte.
void expect_same_files(const std::filesystem::path& a, const std::filesystem::path& b) {
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(a)) {
    if (entry.path().extension() != ".csv") continue;
    const std::filesystem::path other = b / entry.path().filename();
    ASSERT_TRUE(std::filesystem::exists(other)) << other;
    EXPECT_EQ(file_text(entry.path()), file_text(other)) << entry.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 4);  // footprint motion and forces, the interface, the contacts
}

void expect_threads_agree(const std::string& name, nlohmann::json s) {
  s["coupling"]["type"] = "jacobi";
  s["coupling"]["params"]["threads"] = 1;
  const auto one = run(name + "_1", s);
  s["coupling"]["params"]["threads"] = 2;
  const auto two = run(name + "_2", s);
  expect_same_files(one, two);
}

TEST(JacobiThreads, TwoThreadsGiveTheResultsOfOneOnTheFemSoil) {
  expect_threads_agree("jacobi_threads_fem", small_fem_scenario());
}

TEST(JacobiThreads, TwoThreadsGiveTheResultsOfOneWithAnAdaptiveStep) {
  nlohmann::json s = dip_scenario(0.03, 2.5e-5);
  s["coupling"]["params"] = {
      {"adaptive", {{"min_step", 1e-4}, {"max_step", 2e-3}, {"tolerance", 0.05}}}};
  expect_threads_agree("jacobi_threads_adaptive", s);
}

}  // namespace
}  // namespace rumble::testing
