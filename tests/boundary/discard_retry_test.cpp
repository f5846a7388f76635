// DISCARD means one thing: the participant refused the step and its state is unchanged; the host
// passes it to an ABI 1.1 coupler, which takes the step again as halves. picky_soil refuses any
// step longer than max_step, so a run at H = 1 ms on a soil that takes at most 0.25 ms must be
// exactly the run at H = 0.25 ms: the same accepted steps in the same order, the same numbers.
// Per macro step the soil refuses H once and H/2 twice: 3 refusals. Times are binary fractions
// (H = 1/1024 s), so that the halves' start times are exact and "the same" can mean the same bytes.
#include <gtest/gtest.h>

#include "boundary_support.hpp"

namespace rumble::testing {
namespace {

constexpr double kMacro = 1.0 / 1024;    // s
constexpr double kQuarter = kMacro / 4;  // s
constexpr std::size_t kMacroSteps = 50;

nlohmann::json picky(double max_step) {
  return {{"type", "picky_soil"}, {"params", {{"max_step", max_step}}}};
}

void expect_same_as_small_steps(const nlohmann::json& coupling, const std::string& name,
                                std::size_t macro_steps = kMacroSteps) {
  nlohmann::json refused = fixture_scenario(picky(kQuarter), coupling);
  refused["time"] = {{"end", macro_steps * kMacro}, {"macro_step", kMacro}};
  nlohmann::json reference = fixture_scenario(picky(1.0), coupling);
  reference["time"] = {{"end", macro_steps * kMacro}, {"macro_step", kQuarter}};
  CliResult a, b;
  const auto dir_a = run_in(name + "_refused", refused, a);
  const auto dir_b = run_in(name + "_reference", reference, b);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  for (const char* file : {"contact.csv", "vehicles.csv", "footprint_force.csv",
                           "footprint_displacement.csv", "footprint_velocity.csv", "interface.csv"})
    EXPECT_TRUE(same_bytes(dir_a / file, dir_b / file)) << file << " differs";
  const auto summary = read_json(dir_a / "summary.json");
  const auto& by_group = summary["interface"]["max_relative_residual_by_group"];
  EXPECT_TRUE(by_group.contains("footprint_displacement")) << by_group;
  EXPECT_EQ(read_json(dir_b / "summary.json")["interface"]["max_relative_residual_by_group"],
            by_group);
  EXPECT_EQ(summary["coupling"]["discarded_steps"], 3 * macro_steps);
  EXPECT_EQ(summary["time"]["macro_steps"], 4 * macro_steps);  // accepted steps, as reported
  const auto plugin_side = nlohmann::json::parse(file_text(dir_a / "finalized.json"));
  EXPECT_EQ(plugin_side["refusals"], 3 * macro_steps);
  EXPECT_EQ(plugin_side["advances"], 4 * macro_steps);
}

TEST(DiscardRetry, GaussSeidelHalvesARefusedStep) {
  expect_same_as_small_steps({{"type", "gauss_seidel"}}, "discard_gauss_seidel");
}

TEST(DiscardRetry, GaussSeidelHalvesWithLinearExtrapolationToo) {
  // Extrapolation uses the recorded step times, so variable steps give the small-step run. On
  // this massless soil linear extrapolation diverges (decision 0004): a footprint passes twice
  // its static settlement at 0.0122 s and 20 times (the divergence stop) at 0.0149 s. The
  // comparison stops before (12 steps of 0.977 ms).
  expect_same_as_small_steps({{"type", "gauss_seidel"}, {"params", {{"extrapolation", 1}}}},
                             "discard_gauss_seidel_linear", 12);
}

TEST(DiscardRetry, JacobiRestoresTheTrackAndHalves) {
  expect_same_as_small_steps({{"type", "jacobi"}}, "discard_jacobi");
}

// ABI 1.7: the single wheel never refuses a step (RUMBLE_CAP_NEVER_REFUSES), so no scheme keeps
// the soil's checkpoint for a refusal of the track's; the soil's own checkpoints count what was
// kept. An adaptive step that may be retaken still needs both (the test's control).
TEST(DiscardRetry, NoSoilCheckpointForATrackThatNeverRefuses) {
  const struct {
    nlohmann::json coupling;
    long checkpoints;  // -1: at least one per macro step
  } cases[] = {
      {{{"type", "jacobi"}}, 0},
      {{{"type", "jacobi"}, {"params", {{"threads", 1}}}}, 0},
      {{{"type", "gauss_seidel"}, {"params", {{"order", "soil_first"}}}}, 0},
      {{{"type", "jacobi"},
        {"params", {{"adaptive", {{"min_step", kMacro / 8}, {"max_step", kMacro}}}}}},
       -1},
  };
  int k = 0;
  for (const auto& c : cases) {
    nlohmann::json scenario = fixture_scenario(picky(1.0), c.coupling);
    CliResult r;
    const auto dir = run_in("never_refuses_" + std::to_string(k++), scenario, r);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto plugin_side = nlohmann::json::parse(file_text(dir / "finalized.json"));
    if (c.checkpoints >= 0)
      EXPECT_EQ(plugin_side["checkpoints"], c.checkpoints) << c.coupling;
    else
      EXPECT_GE(plugin_side["checkpoints"].get<long>(), plugin_side["advances"].get<long>() / 2)
          << c.coupling;
  }
}

TEST(DiscardRetry, APromiseNeverToRefuseIsHeldToIt) {
  nlohmann::json scenario = fixture_scenario(
      {{"type", "boastful_soil"}, {"params", {{"max_step", kQuarter}}}}, {{"type", "jacobi"}});
  scenario["time"] = {{"end", 4 * kMacro}, {"macro_step", kMacro}};
  CliResult r;
  run_in("never_refuses_broken", scenario, r);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("boastful_soil"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("although its type declares it never does (capability never_refuses"),
            std::string::npos)
      << r.output;
}

TEST(DiscardRetry, ImplicitHalvesARefusedStep) {
  // Iterated to convergence: the soil advances several times per accepted step, so the plugin's
  // advance count is not 4 per macro step; the refused attempts fail on the soil's first advance
  // and leave nothing behind (no accelerator update, no reused column), so the run is the
  // small-step run byte for byte, with every acceleration.
  for (const char* method : {"iqn_ils", "aitken", "constant"}) {
    const nlohmann::json coupling = {{"type", "implicit"}, {"params", {{"acceleration", method}}}};
    nlohmann::json refused = fixture_scenario(picky(kQuarter), coupling);
    refused["time"] = {{"end", kMacroSteps * kMacro}, {"macro_step", kMacro}};
    nlohmann::json reference = fixture_scenario(picky(1.0), coupling);
    reference["time"] = {{"end", kMacroSteps * kMacro}, {"macro_step", kQuarter}};
    CliResult a, b;
    const std::string name = std::string("discard_implicit_") + method;
    const auto dir_a = run_in(name + "_refused", refused, a);
    const auto dir_b = run_in(name + "_reference", reference, b);
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    for (const char* file : {"contact.csv", "footprint_force.csv", "footprint_displacement.csv",
                             "footprint_velocity.csv", "interface.csv"})
      EXPECT_TRUE(same_bytes(dir_a / file, dir_b / file)) << method << ": " << file << " differs";
    const auto summary = read_json(dir_a / "summary.json");
    EXPECT_EQ(summary["coupling"]["discarded_steps"], 3 * kMacroSteps) << method;
    EXPECT_EQ(summary["time"]["macro_steps"], 4 * kMacroSteps) << method;
    EXPECT_EQ(summary["coupling"]["iterations"],
              read_json(dir_b / "summary.json")["coupling"]["iterations"])
        << method;
    EXPECT_EQ(nlohmann::json::parse(file_text(dir_a / "finalized.json"))["refusals"],
              3 * kMacroSteps);
  }
}

TEST(DiscardRetry, ImplicitStopsWhenNoHalvingIsLeft) {
  CliResult r;
  const auto dir =
      run_in("discard_implicit_no_halvings",
             fixture_scenario(picky(kQuarter),
                              {{"type", "implicit"}, {"params", {{"max_step_halvings", 1}}}}),
             r);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("participant 'soil' refused the step starting at t = 0.000000 s"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("max_step_halvings (1) reached"), std::string::npos) << r.output;
}

TEST(DiscardRetry, APluginThatKeepsItsOwnCheckpointsIsNeverCopied) {
  // jacobi checkpoints each participant at every step start when the other may refuse (here
  // both: an ABI 1.1 vehicle does not say that it never refuses); picky_soil declares its own
  // checkpoints, so its state never crosses the boundary (a large FEM state is not copied).
  CliResult r;
  nlohmann::json s = fixture_scenario(picky(kQuarter), {{"type", "jacobi"}});
  s["vehicles"][0]["type"] = "fixture_wheel_1_1";
  s["time"] = {{"end", 8 * kMacro}, {"macro_step", kMacro}};
  const auto dir = run_in("discard_own_checkpoints", s, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto soil = nlohmann::json::parse(file_text(dir / "finalized.json"));
  EXPECT_EQ(soil["state_copies"], 0);
  EXPECT_EQ(soil["checkpoints"], 8 * 7);  // attempts per step: H, 2 x H/2, 4 x H/4
}

TEST(DiscardRetry, NoHalvingsAllowedStopsWithTheReason) {
  CliResult r;
  const auto dir =
      run_in("discard_no_halvings",
             fixture_scenario(picky(kQuarter),
                              {{"type", "gauss_seidel"}, {"params", {{"max_step_halvings", 0}}}}),
             r);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("participant 'soil' refused the step starting at t = 0.000000 s"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("max_step_halvings (0) reached"), std::string::npos) << r.output;
  EXPECT_EQ(read_json(dir / "summary.json")["status"], "failed");
}

// two_step takes no step twice: a refusal in either step stops the run naming the participant,
// the step of the model and the fix.
TEST(DiscardRetry, TwoStepStopsAtARefusalInEitherStep) {
  const nlohmann::json winkler = {{"type", "winkler"}, {"params", {{"k", 1e8}, {"c", 2e5}}}};
  const auto two_step = [](const nlohmann::json& reduced) {
    return nlohmann::json{{"type", "two_step"},
                          {"params", nlohmann::json::object()},
                          {"participants", {{"reduced_soil", reduced}}}};
  };
  CliResult first, second;
  run_in("discard_two_step_1", fixture_scenario(winkler, two_step(picky(kQuarter))), first);
  EXPECT_EQ(first.exit_code, 3) << first.output;
  EXPECT_NE(first.output.find("participant 'reduced_soil' refused the step starting at t = "
                              "0.000000 s"),
            std::string::npos)
      << first.output;
  EXPECT_NE(first.output.find("two_step does not retry steps (step 1 of 2)"), std::string::npos)
      << first.output;
  EXPECT_NE(first.output.find("reduce time.macro_step"), std::string::npos) << first.output;
  run_in("discard_two_step_2", fixture_scenario(picky(kQuarter), two_step(winkler)), second);
  EXPECT_EQ(second.exit_code, 3) << second.output;
  EXPECT_NE(second.output.find("participant 'soil' refused the step starting at t = 0.000000 s"),
            std::string::npos)
      << second.output;
  EXPECT_NE(second.output.find("(step 2 of 2)"), std::string::npos) << second.output;
}

TEST(DiscardRetry, AnAbi10CouplerStillSeesARefusalAsAnError) {
  // 1.0 promised that a refused step stops the run; a 1.0 coupler never learns of DISCARD.
  CliResult r;
  const auto dir = run_in("discard_abi_1_0",
                          fixture_scenario(picky(kQuarter), {{"type", "fixture_coupler_1_0"}}), r);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("advance refused: picky_soil takes steps of at most"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace rumble::testing
