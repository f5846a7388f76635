// End-to-end runs through the CLI with the real in-tree plugins: results on disk, summary,
// and the two couplers agreeing with each other as the macro step shrinks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_runner.hpp"
#include "sanitizer.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

TEST(CliRun, GaussSeidelRunWritesResultsAndSummary) {
  const auto dir = scratch_directory("gs_run");
  const auto path = write_scenario(dir, small_scenario());
  const CliResult r = run_rumble({"run", path.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto results = dir / "results";
  const auto summary = read_json(results / "summary.json");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["time"]["macro_steps"], 50);
  EXPECT_NEAR(summary["static"]["wheel_loads_N"][0].get<double>(), 50000.0 + 750.0 * 9.81, 1e-3);
  EXPECT_EQ(summary["scenario"]["name"], "cli test: single wheel on winkler");
  EXPECT_TRUE(summary["wall_time_s"].contains("vehicle/track"));
  EXPECT_TRUE(summary["wall_time_s"].contains("recording"));
  // Each phase's peak resident memory (core/peak_memory.hpp): a process of some MB at least.
  for (const char* phase : {"build", "statics", "stepping"})
    EXPECT_GT(summary["memory"]["peak_resident_bytes"][phase].get<double>(), 1e6) << phase;
  // An explicit scheme: one iteration per step, every step converged.
  EXPECT_EQ(summary["coupling"]["iterations"]["total"], 50);
  EXPECT_EQ(summary["coupling"]["iterations"]["max_per_step"], 1);
  EXPECT_EQ(summary["coupling"]["unconverged_steps"], 0);
  for (const char* f : {"contact.csv", "vehicles.csv", "footprint_force.csv",
                        "footprint_displacement.csv", "footprint_velocity.csv", "interface.csv"})
    EXPECT_EQ(csv_rows(results / f), 51u) << f;  // t = 0 and 50 macro steps
}

// Memory per DOF (issue #33): the FEM soil states its DOFs and its estimate of the run's peak
// (ABI 1.5 size), summary.json divides each phase's peak by them, and the soil frees its statics'
// factor when the engine says the statics are done (statics_done), so that the steps hold about
// what the build did. Before, on this 1.9e4-DOF mesh: build 91 MB, statics 203 MB, and the steps
// 175 MB, the factor kept (docs/fem-soil.md section 7.2).
TEST(CliRun, AFemRunAccountsItsMemoryPerDofAndFreesItsStaticsBeforeTheSteps) {
  const auto dir = scratch_directory("fem_memory");
  nlohmann::json s = small_fem_scenario();
  s["track"]["sleepers"]["count"] = 30;
  s["soil"]["params"]["mesh"] = {{"radius", 15.0}, {"f_max", 50.0}, {"near_distance", 5.0}};
  s["time"]["end"] = 5e-3;  // s
  s["outputs"]["plots"] = false;
  const auto path = write_scenario(dir, s);
  const CliResult r = run_rumble({"run", path.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("estimates the run's peak resident memory at"));
  EXPECT_THAT(r.output, HasSubstr("times the peak"));
  const auto memory = read_json(dir / "results" / "summary.json")["memory"];
  const double dofs = memory["soil_dofs"].get<double>();
  EXPECT_GT(dofs, 1e4);
  for (const char* phase : {"build", "statics", "stepping"})
    EXPECT_NEAR(memory["bytes_per_dof"][phase].get<double>(),
                memory["peak_resident_bytes"][phase].get<double>() / dofs, 1e-6)
        << phase;
  if (test::kUnderAddressSanitizer) GTEST_SKIP() << "resident memory under AddressSanitizer";
  // The soil's estimate (memory_model.hpp): 0.87 times the peak here.
  EXPECT_GT(memory["estimate_over_peak"].get<double>(), 0.7);
  EXPECT_LT(memory["estimate_over_peak"].get<double>(), 1.3);
  const auto& peak = memory["peak_resident_bytes"];
  EXPECT_GT(peak["statics"].get<double>(), peak["stepping"].get<double>() + 50e6);  // the factor
  EXPECT_LT(peak["stepping"].get<double>(), peak["build"].get<double>() + 20e6);
}

/// All values of a CSV file (header skipped), row by row.
std::vector<std::vector<double>> read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::size_t start = 0;
    while (start <= line.size()) {
      const std::size_t end = line.find(',', start);
      row.push_back(std::stod(line.substr(start, end - start)));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<std::vector<double>> run_displacements(const std::string& name,
                                                   const nlohmann::json& scenario) {
  const auto dir = scratch_directory(name);
  const CliResult r = run_rumble({"run", write_scenario(dir, scenario).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return read_csv(dir / "results" / "footprint_displacement.csv");
}

// Gauss-Seidel and Jacobi are both consistent, first-order schemes: the largest difference of
// their footprint displacement histories, relative to the largest displacement, shrinks about
// 10x from H = 1 ms to 0.1 ms (docs/couplers.md, "Expected error of the explicit schemes"); > 4x
// is required to stay robust.
TEST(CliRun, CouplersConvergeTogetherAsTheMacroStepShrinks) {
  std::vector<double> differences;
  for (double H : {1e-3, 1e-4}) {
    nlohmann::json s = small_scenario();
    s["time"]["end"] = 0.02;
    s["time"]["macro_step"] = H;
    const auto gs = run_displacements("gs_" + std::to_string(H), s);
    s["coupling"]["type"] = "jacobi";
    const auto jacobi = run_displacements("jacobi_" + std::to_string(H), s);
    ASSERT_EQ(gs.size(), jacobi.size());
    double diff = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < gs.size(); ++k) {
      for (std::size_t i = 1; i < gs[k].size(); ++i) {
        diff = std::max(diff, std::abs(gs[k][i] - jacobi[k][i]));
        scale = std::max(scale, std::abs(gs[k][i]));
      }
    }
    ASSERT_GT(scale, 0.0);
    differences.push_back(diff / scale);
  }
  EXPECT_GT(differences[0], 0.0);
  EXPECT_GT(differences[0] / std::max(differences[1], 1e-15), 4.0)
      << differences[0] << " " << differences[1];
}

}  // namespace
}  // namespace rumble::testing
