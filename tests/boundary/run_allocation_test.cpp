// A whole coupled run allocates nothing per macro step: the coupler (gauss_seidel, also with an
// adaptive step, jacobi, implicit, monolithic), the host and its step reports, both participants
// through their plugin tables, the recorder, the receiver samples and summary.json's heartbeat
// (here after every step). Measured as the difference between a run of N and of 2N macro steps of
// the same scenario (setup and summary cost the same in both): a per-step allocation would show as
// at least N. The summary's numbers differ in length between the two runs, so a handful of string
// growths may differ: the bound is 10 with N = 50.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "boundary_support.hpp"
#include "cli/scenario_prepare.hpp"
#include "run/run_scenario.hpp"

namespace rumble::testing {
namespace {

constexpr long kSteps = 50;

long allocations_of_run(const std::string& name, nlohmann::json s, long steps) {
  s["time"] = {{"end", steps * 1e-3}, {"macro_step", 1e-3}};
  const auto dir = scratch_directory(name);
  const auto path = write_scenario(dir, s);
  PluginRegistry registry;
  auto doc = cli::prepare_scenario(path, registry, scenario::Format::kText);
  EXPECT_TRUE(doc.has_value());
  const scenario::RunSpec spec = scenario::make_run_spec(doc->json, path);
  ResultsDirectory results(spec.outputs.directory, spec.path, false);
  const AllocationCounter counter;
  RunOptions options;
  options.heartbeat_seconds = 0.0;  // a heartbeat write after every macro step
  const RunOutcome outcome = run_scenario(spec, registry, results, options);
  EXPECT_EQ(outcome.status, RunStatus::kCompleted) << outcome.message;
  return counter.count();
}

void expect_no_allocation_per_step(const std::string& name, const nlohmann::json& s) {
  const long short_run = allocations_of_run(name + "_n", s, kSteps);
  const long long_run = allocations_of_run(name + "_2n", s, 2 * kSteps);
  EXPECT_LE(std::abs(long_run - short_run), 10) << short_run << " allocations for " << kSteps
                                                << " steps, " << long_run << " for " << 2 * kSteps;
}

TEST(RunAllocation, GaussSeidelWithReceivers) {
  nlohmann::json s = fixture_scenario({{"type", "picky_soil"}}, {{"type", "gauss_seidel"}});
  s["outputs"]["receivers"] = {2.5, 5.0};
  s["vehicles"][0]["start"] = 1.0;
  expect_no_allocation_per_step("run_allocation_gs", s);
}

TEST(RunAllocation, JacobiOnTwoThreadsWithCheckpoints) {
  // Two threads: the soil advances on a worker kept for the run (a thread per step would
  // allocate its stack); jacobi checkpoints every step.
  nlohmann::json s = small_scenario();
  s["coupling"] = {{"type", "jacobi"}, {"params", {{"threads", 2}}}};
  s["vehicles"][0]["start"] = 1.0;
  expect_no_allocation_per_step("run_allocation_jacobi", s);
}

TEST(RunAllocation, GaussSeidelWithAnAdaptiveStep) {
  // Steps of 0.25 to 2 ms, some taken again (both participants checkpoint every step); each
  // change of length refactors the track and the soil in place.
  nlohmann::json s = small_scenario();
  s["coupling"] = {
      {"type", "gauss_seidel"},
      {"params", {{"adaptive", {{"min_step", 2.5e-4}, {"max_step", 2e-3}, {"tolerance", 0.5}}}}}};
  s["vehicles"][0]["start"] = 1.0;
  expect_no_allocation_per_step("run_allocation_gs_adaptive", s);
}

TEST(RunAllocation, ImplicitIqnIls) {
  // Iterated every step, with columns reused from past steps; the soil checkpoints every step.
  nlohmann::json s = small_scenario();
  s["coupling"] = {{"type", "implicit"}, {"params", {{"acceleration", "iqn_ils"}}}};
  s["vehicles"][0]["start"] = 1.0;
  expect_no_allocation_per_step("run_allocation_implicit", s);
}

TEST(RunAllocation, Monolithic) {
  // The soil condensed onto the sleepers in every micro-step (work space sized once).
  nlohmann::json s = small_scenario();
  s["coupling"] = {{"type", "monolithic"}, {"params", nlohmann::json::object()}};
  s["vehicles"][0]["start"] = 1.0;
  expect_no_allocation_per_step("run_allocation_monolithic", s);
}

}  // namespace
}  // namespace rumble::testing
