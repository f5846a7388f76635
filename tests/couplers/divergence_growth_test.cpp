// A diverging run is told by its growth, not its size (issue #29, run/growth_watch.hpp): three
// couplings that `rumble stability` predicts unstable, each stopped while the footprint motion is
// still small, with the growth rate per macro step in the message and in summary.json. Each ran
// to `completed` or was caught only at 10 m/s before. Their stable twins complete.
//   - the paper's track over a massless CLM (E = 60 MPa), Gauss-Seidel at 0.5 ms: predicted
//     1.041 per step; the run's speed later grows 1.041 per step (footprint_velocity.csv,
//     0.17-0.25 s), to 218 m/s at 0.25 s, and was `completed` with 0.26 m/s and more;
//   - the small track over the soft CLM with 50 kg per footprint, Jacobi at 1 ms: predicted 1.244;
//   - the small track on a soft FEM soil (E = 10 MPa, a 3.3e4-DOF mesh), Jacobi at 1 ms: its
//     speed grows about 1.045 per step (0.14-0.18 s) to 0.59 m/s at 0.2 s, which completed;
//     Gauss-Seidel at 1 ms completes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "sanitizer.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

struct Diverged {
  nlohmann::json divergence;   // summary.json's
  double largest_speed = 0.0;  // m/s, |footprint velocity| over the run as recorded
};

Diverged run_diverging(const std::string& name, const nlohmann::json& s) {
  const auto dir = scratch_directory(name);
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("footprint speeds grow exponentially, by "));
  EXPECT_THAT(r.output, HasSubstr("an unstable coupling, not the train"));
  Diverged d;
  d.divergence = read_json(dir / "results" / "summary.json").at("divergence");
  std::vector<double> t, v;
  read_csv(dir / "results" / "footprint_velocity.csv", t, v);
  for (double x : v) d.largest_speed = std::max(d.largest_speed, std::abs(x));
  return d;
}

TEST(DivergenceGrowth, TheMasslessClmOfIssue29StopsEarlyWithItsRate) {
  std::ifstream in(std::string(RUMBLE_TEST_SOURCE_DIR) +
                   "/scenarios/paper/medium_soil_gauss_seidel.json");
  nlohmann::json s = nlohmann::json::parse(in);
  s["soil"]["params"]["E"] = 60e6;
  s["time"] = {{"end", 0.25}, {"macro_step", 5e-4}};
  s["outputs"] = {{"directory", "results"}, {"plots", false}};
  const Diverged d = run_diverging("growth_massless_clm", s);
  EXPECT_TRUE(d.divergence.at("detected").get<bool>());
  EXPECT_NEAR(d.divergence.at("growth_per_macro_step").get<double>(), 1.041, 0.008);
  EXPECT_LT(d.divergence.at("t_detected_s").get<double>(), 0.16);
  EXPECT_LT(d.largest_speed, 0.1);  // m/s: the train's own is 8-12 mm/s
}

TEST(DivergenceGrowth, JacobiOnTheSoftClmWithLittleMassAgreesWithTheStabilityAnalysis) {
  nlohmann::json s = small_scenario();
  s["time"]["end"] = 0.3;
  s["soil"] = {{"type", "clm"},
               {"params", {{"E", 1e7}, {"nu", 0.3}, {"rho", 1800.0}, {"m_f", 50.0}}}};
  s["coupling"]["type"] = "jacobi";
  const Diverged d = run_diverging("growth_soft_clm_jacobi", s);
  EXPECT_NEAR(d.divergence.at("growth_per_macro_step").get<double>(), 1.244, 0.03);
  EXPECT_LT(d.largest_speed, 10.0);  // m/s: the size bound no longer has to catch it
}

TEST(DivergenceGrowth, JacobiOnASoftFemSoilStopsGaussSeidelCompletes) {
  ::setenv("RUMBLE_MESH_CACHE", (std::string(RUMBLE_TEST_BINARY_DIR) + "/mesh_cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.2;
  s["vehicles"][0]["speed"] = 15.0;
  s["vehicles"][0]["start"] = 1.2;
  s["soil"]["params"]["E"] = 1e7;
  s["soil"]["params"]["mesh"]["f_max"] = 20.0;
  s["coupling"]["type"] = "jacobi";
  const Diverged d = run_diverging("growth_soft_fem_jacobi", s);
  EXPECT_GT(d.divergence.at("growth_per_macro_step").get<double>(), 1.02);
  EXPECT_LT(d.divergence.at("growth_per_macro_step").get<double>(), 1.08);
  EXPECT_LT(d.largest_speed, 0.3);  // m/s: 0.59 by 0.2 s if left to run
  if (rumble::test::kUnderAddressSanitizer) ::unsetenv("RUMBLE_MESH_CACHE");
  RUMBLE_PHYSICS_IN_THE_DEV_BUILD_ONLY();  // (Gauss-Seidel's whole run: the FEM path as above)
  s["coupling"]["type"] = "gauss_seidel";
  const auto dir = scratch_directory("growth_soft_fem_gauss_seidel");
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(read_json(dir / "results" / "summary.json")["divergence"]["detected"].get<bool>());
}

}  // namespace
}  // namespace rumble::testing
