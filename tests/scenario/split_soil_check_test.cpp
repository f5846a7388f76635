// What needs a soil's whole matrices, against a soil split over MPI ranks (check_split_soil,
// scenario/capability_check.hpp; issue #33): a monolithic coupler, and a command that reads the
// whole operator (`rumble stability`, `soil-frf`, `calibrate`), with a distributed soil (fem) on
// N > 1 ranks are refused by validation, naming the pointer, the value, the soil function and
// the fix; the same on one process, with a coupler that steps the soil, or with a soil that
// runs on one rank (winkler) pass. The in-tree plugins' declared capabilities are read, so the
// test fails if fem stops declaring RUMBLE_CAP_DISTRIBUTED or monolithic RUMBLE_CAP_MONOLITHIC.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "plugin/registry.hpp"
#include "scenario/capability_check.hpp"

namespace rumble::scenario::split_soil_check {

using nlohmann::json;

json scenario_with(const std::string& soil, const std::string& coupler) {
  return {{"soil", {{"type", soil}, {"params", json::object()}}},
          {"coupling", {{"type", coupler}, {"params", json::object()}}}};
}

TEST(SplitSoil, MonolithicCouplerWithADistributedSoilOnRanksIsRefusedAtCouplingType) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  const std::vector<Diagnostic> found =
      check_split_soil(scenario_with("fem", "monolithic"), registry, 2);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].pointer, "/coupling/type");
  EXPECT_NE(found[0].message.find("coupler \"monolithic\""), std::string::npos) << found[0].message;
  EXPECT_NE(found[0].message.find("split over the 2 MPI ranks"), std::string::npos);
  EXPECT_NE(found[0].message.find("its linear_matrix"), std::string::npos) << found[0].message;
  EXPECT_NE(found[0].hint.find("without mpirun"), std::string::npos) << found[0].hint;
  EXPECT_NE(found[0].hint.find("got \"monolithic\""), std::string::npos) << found[0].hint;
}

constexpr WholeSoilCommand kStability{"rumble stability", "it linearizes the track on the soil",
                                      "linear_matrix"};

TEST(SplitSoil, StabilityWithADistributedSoilOnRanksIsRefusedAtSoilType) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  const std::vector<Diagnostic> found =
      check_split_soil(scenario_with("fem", "gauss_seidel"), registry, 3, kStability);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].pointer, "/soil/type");
  EXPECT_NE(found[0].message.find("rumble stability (it linearizes the track on the soil)"),
            std::string::npos)
      << found[0].message;
  EXPECT_NE(found[0].message.find("3 MPI ranks"), std::string::npos) << found[0].message;
  EXPECT_NE(found[0].hint.find("run rumble stability without mpirun"), std::string::npos)
      << found[0].hint;
}

TEST(SplitSoil, TheReceptanceOfADistributedSoilOnRanksIsRefusedAtSoilType) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  const WholeSoilCommand frf{"rumble soil-frf", "the soil's receptance", "frequency_response"};
  const std::vector<Diagnostic> found =
      check_split_soil(scenario_with("fem", "gauss_seidel"), registry, 2, frf);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].pointer, "/soil/type");
  EXPECT_NE(found[0].message.find("rumble soil-frf (the soil's receptance) needs the whole "
                                  "matrices of soil type \"fem\" (/soil, its frequency_response)"),
            std::string::npos)
      << found[0].message;
  EXPECT_NE(found[0].hint.find("run rumble soil-frf without mpirun"), std::string::npos)
      << found[0].hint;
}

TEST(SplitSoil, OneProcessASteppingCouplerOrASoilOnOneRankPass) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  EXPECT_TRUE(
      check_split_soil(scenario_with("fem", "monolithic"), registry, 1, kStability).empty());
  EXPECT_TRUE(check_split_soil(scenario_with("fem", "gauss_seidel"), registry, 2).empty());
  EXPECT_TRUE(check_split_soil(scenario_with("fem", "implicit"), registry, 2).empty());
  EXPECT_TRUE(
      check_split_soil(scenario_with("winkler", "monolithic"), registry, 2, kStability).empty());
}

}  // namespace rumble::scenario::split_soil_check
