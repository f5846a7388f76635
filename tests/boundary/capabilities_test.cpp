// `rumble validate` matches what a scenario's components need against what they declare
// (ABI 1.1 capabilities) before anything runs, and says where (JSON pointer), what and how to
// fix it. Fixtures: needy_coupler needs save/restore of every soil, a participant
// "reduced_soil" and macro steps <= 1 ms; forgetful_soil cannot save/restore and allows one
// instance per process; picky_soil can save/restore and offers receivers.
#include <gtest/gtest.h>

#include "boundary_support.hpp"

namespace rumble::testing {
namespace {

nlohmann::json needy(const nlohmann::json& participants) {
  return {{"type", "needy_coupler"}, {"participants", participants}};
}
const nlohmann::json kPicky = {{"type", "picky_soil"}};
const nlohmann::json kForgetful = {{"type", "forgetful_soil"}};

/// `rumble validate` output for the scenario, and its exit code.
CliResult validate(const std::string& name, const nlohmann::json& scenario) {
  const auto dir = scratch_directory(name);
  return run_rumble({"validate", write_scenario(dir, scenario).string()});
}

void expect_error(const CliResult& r, const std::string& pointer, const std::string& text) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(pointer), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(text), std::string::npos) << r.output;
}

TEST(Capabilities, ASoilThatCannotSaveIsRefusedForACouplerThatNeedsIt) {
  const CliResult r =
      validate("caps_save", fixture_scenario(kForgetful, needy({{"reduced_soil", kPicky}})));
  expect_error(r, "/soil/type",
               "soil type \"forgetful_soil\" cannot save and restore its state, which coupler "
               "\"needy_coupler\" needs of every soil it drives");
  EXPECT_NE(r.output.find("choose a soil that can ("), std::string::npos) << r.output;
}

TEST(Capabilities, TheMonolithicCouplerRefusesASoilWithoutLinearMatrices) {
  // It integrates the soil's M, C, K and B inside the track (decision 0008).
  const CliResult r =
      validate("caps_monolithic", fixture_scenario(kForgetful, {{"type", "monolithic"}}));
  expect_error(r, "/soil/type", "linear matrices");
}

TEST(Capabilities, StabilityAnalysisTakesASoilWithoutLinearMatricesOrCheckpoints) {
  // It steps the soil plugin as a run does (analysis/coupling_stability.hpp): nothing but what
  // every soil offers is needed.
  const auto dir = scratch_directory("caps_stability");
  const nlohmann::json s = fixture_scenario(kForgetful, {{"type", "gauss_seidel"}});
  const CliResult r =
      run_rumble({"stability", write_scenario(dir, s).string(), "--macro-steps", "1e-3"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0.001 "), std::string::npos) << r.output;
}

TEST(Capabilities, TheImplicitCouplerRefusesASoilThatCannotSave) {
  // It takes every macro step several times from checkpoints (declared kSoilNeeds).
  const CliResult r =
      validate("caps_implicit", fixture_scenario(kForgetful, {{"type", "implicit"}}));
  expect_error(r, "/soil/type",
               "soil type \"forgetful_soil\" cannot save and restore its state, which coupler "
               "\"implicit\" needs of every soil it drives");
  EXPECT_NE(r.output.find("choose a soil that can ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("picky_soil"), std::string::npos) << r.output;
  EXPECT_EQ(
      validate("caps_implicit_ok", fixture_scenario(kPicky, {{"type", "implicit"}})).exit_code, 0);
}

TEST(Capabilities, TheNeedAppliesToExtraParticipantsToo) {
  const CliResult r =
      validate("caps_extra", fixture_scenario(kPicky, needy({{"reduced_soil", kForgetful}})));
  expect_error(r, "/coupling/participants/reduced_soil/type",
               "soil type \"forgetful_soil\" cannot save and restore its state");
}

TEST(Capabilities, AMissingParticipantIsNamed) {
  const CliResult r =
      validate("caps_missing", fixture_scenario(kPicky, needy(nlohmann::json::object())));
  expect_error(r, "/coupling",
               "coupler \"needy_coupler\" needs a participant \"reduced_soil\" (the soil of the "
               "first pass)");
  EXPECT_NE(r.output.find("add /coupling/participants/reduced_soil"), std::string::npos);
}

TEST(Capabilities, AnUnknownParticipantIsNamed) {
  const CliResult r =
      validate("caps_unknown",
               fixture_scenario(kPicky, needy({{"reduced_soil", kPicky}, {"spare_soil", kPicky}})));
  expect_error(r, "/coupling/participants/spare_soil",
               "coupler \"needy_coupler\" drives no participant \"spare_soil\"");
  EXPECT_NE(r.output.find("its participants are: reduced_soil"), std::string::npos);
}

TEST(Capabilities, ACouplerWithoutExtraParticipantsRefusesThem) {
  nlohmann::json c = {{"type", "gauss_seidel"}, {"participants", {{"reduced_soil", kPicky}}}};
  const CliResult r = validate("caps_gs_extra", fixture_scenario(kPicky, c));
  expect_error(r, "/coupling/participants/reduced_soil",
               "this coupler drives only the track and /soil; remove it");
}

TEST(Capabilities, AMacroStepBeyondADeclaredLimitIsRefused) {
  nlohmann::json s = fixture_scenario(kPicky, needy({{"reduced_soil", kPicky}}));
  s["time"]["macro_step"] = 2e-3;
  const CliResult r = validate("caps_max_step", s);
  expect_error(r, "/time/macro_step",
               "must be <= 0.001 s, the largest macro step coupler type \"needy_coupler\" "
               "(/coupling) accepts, got 0.002");
}

TEST(Capabilities, AOncePerProcessTypeUsedTwiceIsRefused) {
  nlohmann::json c = {{"type", "gauss_seidel"}};
  nlohmann::json s = fixture_scenario(
      kForgetful, {{"type", "needy_coupler"}, {"participants", {{"reduced_soil", kForgetful}}}});
  const CliResult r = validate("caps_once", s);
  expect_error(r, "/coupling/participants/reduced_soil/type",
               "type \"forgetful_soil\" allows one instance per process and is already used at "
               "/soil");
}

TEST(Capabilities, ReceiversOnASoilWithoutThemAreAWarningOnly) {
  nlohmann::json s = fixture_scenario(kForgetful, {{"type", "gauss_seidel"}});
  s["outputs"]["receivers"] = {2.5};
  const CliResult r = validate("caps_receivers", s);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("soil type \"forgetful_soil\" offers no receivers"), std::string::npos)
      << r.output;
}

TEST(Capabilities, AScenarioThatMatchesValidates) {
  const CliResult r =
      validate("caps_ok", fixture_scenario(kPicky, needy({{"reduced_soil", kPicky}})));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

}  // namespace
}  // namespace rumble::testing
