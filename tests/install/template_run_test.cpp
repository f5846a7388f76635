// `rumble run` with the out-of-tree template soil named in the scenario's "plugins" list: the
// engine loads it next to its own plugins and runs it through the coupler. The template is a
// massless spring-dashpot per footprint, the same model as the in-tree winkler soil with k and c
// given, so the two runs must agree: a second, independent implementation as the check. The
// template integrates c u' + k u = F exactly, winkler by the trapezoidal rule in sub-steps h,
// whose relative global error is about (h / tau)^2 / 12 with tau = c / k = 2 ms: with
// h = 10 us (winkler's max_step) that is 2e-6, so the runs must agree to 1e-5 of the peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

constexpr double kStiffness = 1.0e8;   // N/m per footprint
constexpr double kDamping = 2.0e5;     // N s/m per footprint
constexpr double kWinklerStep = 1e-5;  // s, winkler's sub-step bound
constexpr double kTolerance = 1e-5;    // of the peak, 5x the trapezoidal error bound above

std::filesystem::path run(const std::string& name, const nlohmann::json& soil,
                          const nlohmann::json& plugins) {
  const auto dir = scratch_directory(name);
  nlohmann::json s = small_scenario();
  s["soil"] = soil;
  if (!plugins.empty()) s["plugins"] = plugins;
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir / "results";
}

TEST(TemplateRun, AgreesWithWinklerOfTheSameSpringAndDashpot) {
  const auto winkler =
      run("template_run_winkler",
          {{"type", "winkler"},
           {"params", {{"k", kStiffness}, {"c", kDamping}, {"max_step", kWinklerStep}}}},
          nlohmann::json::array());
  const auto templ = run(
      "template_run_template",
      {{"type", "template_soil"}, {"params", {{"stiffness", kStiffness}, {"damping", kDamping}}}},
      nlohmann::json::array({TEMPLATE_PLUGIN}));
  EXPECT_EQ(read_json(templ / "summary.json")["status"], "completed");

  for (const char* file : {"footprint_displacement.csv", "contact.csv"}) {
    std::vector<double> times_a, times_b, a, b;
    read_csv(winkler / file, times_a, a);
    read_csv(templ / file, times_b, b);
    EXPECT_EQ(times_a, times_b) << file;
    ASSERT_EQ(a.size(), b.size()) << file;
    ASSERT_GE(times_a.size(), 50u) << file;  // 0.05 s in 1 ms macro steps
    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      scale = std::max(scale, std::abs(a[i]));
      diff = std::max(diff, std::abs(a[i] - b[i]));
    }
    EXPECT_GT(scale, 0.0) << file;
    EXPECT_LE(diff, kTolerance * scale)
        << file << ": largest difference " << diff << " of " << scale;
  }
}

}  // namespace
}  // namespace rumble::testing
