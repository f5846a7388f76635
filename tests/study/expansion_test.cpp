// Expansion of a study into runs: product order and names, patches merged in axis order,
// explicit runs after the product, duplicate names.
#include "study/expansion.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "study_test_support.hpp"

namespace rumble::study {
namespace {

using ::testing::ElementsAre;
using testing::read;

std::vector<PlannedRun> expand_text(const std::string& text, std::vector<std::string>* problems) {
  const auto r = read(text);
  EXPECT_TRUE(r.study) << ::testing::PrintToString(r.problems);
  if (!r.study) return {};
  std::vector<scenario::Diagnostic> d;
  auto runs = expand(*r.study, d);
  for (const auto& x : d) problems->push_back(x.pointer + ": " + x.message + " | " + x.hint);
  return runs;
}

std::vector<std::string> names(const std::vector<PlannedRun>& runs) {
  std::vector<std::string> out;
  for (const auto& r : runs) out.push_back(r.name);
  return out;
}

TEST(Expansion, ProductInAxisOrderThenExplicitRuns) {
  std::vector<std::string> problems;
  const auto runs = expand_text(R"({"study_version": 1, "scenario": "base.json",
    "axes": [{"name": "soil", "values": {"soft": {"/soil/params/E": 1e7, "/x": 1},
                                         "medium": {"/soil/params/E": 1.55e8}}},
             {"name": "coupling", "values": {"gs": {"/coupling/type": "gauss_seidel", "/x": 2},
                                             "jacobi": {"/coupling/type": "jacobi"},
                                             "two": {}}}],
    "runs": [{"name": "extra", "scenario": "other.json", "set": {"/time/macro_step": 1e-4}}]})",
                                &problems);
  EXPECT_TRUE(problems.empty()) << ::testing::PrintToString(problems);
  EXPECT_THAT(names(runs), ElementsAre("soft-gs", "soft-jacobi", "soft-two", "medium-gs",
                                       "medium-jacobi", "medium-two", "extra"));
  // Patches in axis order: the later axis's "/x" comes after, so it wins when applied.
  const PlannedRun& soft_gs = runs[0];
  ASSERT_EQ(soft_gs.patches.size(), 4u);
  EXPECT_EQ(soft_gs.patches[0].pointer, "/soil/params/E");
  EXPECT_EQ(soft_gs.patches[1].pointer, "/x");
  EXPECT_EQ(soft_gs.patches[1].value, 1);
  EXPECT_EQ(soft_gs.patches[2].pointer, "/coupling/type");
  EXPECT_EQ(soft_gs.patches[3].pointer, "/x");
  EXPECT_EQ(soft_gs.patches[3].value, 2);
  nlohmann::json doc = {{"x", 0}};
  std::vector<scenario::Override> o = overrides(soft_gs, "study.json");
  for (auto& x : o) {
    if (x.pointer == "/x") scenario::apply_override(doc, x);
  }
  EXPECT_EQ(doc["x"], 2);
  EXPECT_EQ(o[0].origin, "the study, /axes/0/values/soft/~1soil~1params~1E");
  EXPECT_EQ(o[0].label,
            "study.json: /axes/0/values/soft/~1soil~1params~1E: /soil/params/E = 1e+07");
  EXPECT_EQ(soft_gs.axis_values, nlohmann::ordered_json({{"soil", "soft"}, {"coupling", "gs"}}));
  EXPECT_EQ(soft_gs.scenario, testing::study_folder() / "base.json");
  EXPECT_TRUE(runs[5].patches.size() == 1 && runs[5].patches[0].pointer == "/soil/params/E");
  const PlannedRun& extra = runs.back();
  EXPECT_EQ(extra.scenario, testing::study_folder() / "other.json");
  EXPECT_EQ(extra.source, "/runs/0");
  ASSERT_EQ(extra.patches.size(), 1u);
  EXPECT_EQ(extra.patches[0].pointer, "/time/macro_step");
  EXPECT_TRUE(extra.axis_values.empty());
}

TEST(Expansion, OnlyExplicitRuns) {
  std::vector<std::string> problems;
  const auto runs = expand_text(
      R"({"study_version": 1, "scenario": "base.json", "runs": [{"name": "b"}, {"name": "a"}]})",
      &problems);
  EXPECT_THAT(names(runs), ElementsAre("b", "a"));
  EXPECT_TRUE(runs[0].patches.empty());
}

TEST(Expansion, DuplicateNames) {
  std::vector<std::string> problems;
  const auto runs = expand_text(R"({"study_version": 1, "scenario": "base.json",
    "axes": [{"name": "a", "values": {"x": {}, "x-y": {}}}, {"name": "b", "values": {"y": {}, "z": {}}}],
    "runs": [{"name": "x-z"}]})",
                                &problems);
  EXPECT_TRUE(runs.empty());
  EXPECT_THAT(problems,
              ElementsAre("/runs/0/name: two runs are named 'x-z': the axes (a = x, b = z) and "
                          "the run at /runs/0 | run names name their results directories; rename "
                          "a run or an axis value"));
  problems.clear();
  expand_text(R"({"study_version": 1, "scenario": "base.json",
    "axes": [{"name": "a", "values": {"x": {}, "x-y": {}}}, {"name": "b", "values": {"z": {}, "y-z": {}}}]})",
              &problems);
  EXPECT_THAT(problems,
              ElementsAre("/axes: two runs are named 'x-y-z': the axes (a = x, b = y-z) and the "
                          "axes (a = x-y, b = z) | run names name their results directories; "
                          "rename a run or an axis value"));
}

}  // namespace
}  // namespace rumble::study
