// The adaptive macro step of the explicit couplers (params.adaptive, rumble/macro_steps.hpp)
// through the CLI, against the monolithic reference recorded every min_step (so every adaptive
// step ends on its grid), the track's micro-step fixed at 25 us (it divides every macro step):
//   - on the small Winkler scenario with a rail dip that the wheel reaches after 10 ms: the step
//     stays within its bounds, is a whole number of min_step, ends at time.end, is recorded in
//     interface.csv and summary.json, and is short where the wheel meets the dip; ending inside
//     the dip (two thirds of the run), it still costs less than fixed steps at equal
//     displacement error;
//   - on the paper's dip case (its track on its medium soil as Winkler footprints, the wheel 3.7
//     m before the dip, 0.3 s), its steps shrink at the dip; on its medium soil (Winkler and CLM)
//     and its stiff soil (CLM), its errors fall with the tolerance, and at two tolerances
//     gauss_seidel's costs at most 0.7 times the steps of fixed steps at equal footprint PPV
//     error and at equal displacement error (the fixed steps' count interpolated log-log between
//     the pair that brackets the error; the adaptive cost counts the steps taken again);
//     jacobi's too at equal PPV error, and at most that of fixed steps at equal displacement
//     error;
//   - jacobi adapts on the small scenario too; inverted bounds are refused at validate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli_runner.hpp"
#include "coupler_runs.hpp"
#include "sanitizer.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

constexpr double kMinStep = 5e-5, kMaxStep = 2e-3;  // s
constexpr double kEnd = 0.03;                       // s

nlohmann::json dip(double H) {
  nlohmann::json s = dip_scenario(kEnd, 2.5e-5);
  s["time"]["macro_step"] = H;
  return s;
}

nlohmann::json adaptive_coupler(const std::string& type, double tolerance) {
  return {
      {"type", type},
      {"params",
       {{"adaptive", {{"min_step", kMinStep}, {"max_step", kMaxStep}, {"tolerance", tolerance}}}}}};
}

/// The paper's dip case: one wheel at 25 m/s over the paper's track on one of its soils
/// (scenarios/paper/<file>.json), the wheel starting 3.7 m before the 1 mm dip at 21 m and run
/// 0.3 s (the dip is crossed at 0.15 to 0.17 s), gauss_seidel at H.
nlohmann::json paper_dip(double H, const std::string& file = "medium_soil_winkler") {
  std::ifstream in(std::string(RUMBLE_TEST_SOURCE_DIR) + "/scenarios/paper/" + file + ".json");
  nlohmann::json s = nlohmann::json::parse(in);
  s["vehicles"][0]["start"] = 17.0;  // m
  s["time"] = {{"end", 0.3}, {"macro_step", H}};
  s["track"]["integrator"] = {{"micro_step", 2.5e-5}};
  s["coupling"] = {{"type", "gauss_seidel"}, {"params", nlohmann::json::object()}};
  s["outputs"] = {{"directory", "results"}, {"plots", false}};
  return s;
}

/// The monolithic reference of a scenario at H = min_step (run once per test process). ctest
/// runs each test in its own process, in parallel, so the directory is named after the test
/// that asks first: two tests sharing one directory wiped each other's results (CI, stop 16).
std::filesystem::path monolithic(const std::string& name, nlohmann::json s) {
  s["time"]["macro_step"] = kMinStep;
  s["coupling"] = {{"type", "monolithic"}, {"params", nlohmann::json::object()}};
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  return run(name + "_" + test, s);
}
const std::filesystem::path& reference_dir() {
  static const std::filesystem::path dir = monolithic("adaptive_reference", dip(kMinStep));
  return dir;
}

/// Runs the scenario like run() and also returns how many steps the adaptive coupler took again
/// (its log: "..., N taken again above the tolerance") and how many extra soil advances jacobi's
/// probes of the held force's cost took ("... probed in N extra soil advances"; 0 for others).
std::filesystem::path run_counting_retakes(const std::string& name, const nlohmann::json& s,
                                           std::size_t& retaken, std::size_t* probes = nullptr) {
  const auto dir = scratch_directory(name);
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto count = [&](const char* pattern) -> std::size_t {
    std::smatch m;
    return std::regex_search(r.output, m, std::regex(pattern))
               ? static_cast<std::size_t>(std::stoul(m[1].str()))
               : 0;
  };
  retaken = count("([0-9]+) taken again");
  if (probes != nullptr) *probes = count("probed in ([0-9]+) extra soil advances");
  return dir / "results";
}

/// interface.csv's macro step column (the 7th of 8 after t), without the t = 0 row.
std::vector<double> macro_steps(const std::filesystem::path& dir, std::vector<double>& ends) {
  const Histories h = csv(dir / "interface.csv");
  constexpr std::size_t kColumns = 8;
  std::vector<double> steps;
  ends.clear();
  for (std::size_t k = 1; k < h.times.size(); ++k) {
    steps.push_back(h.values[kColumns * k + 6]);
    ends.push_back(h.times[k]);
  }
  return steps;
}

TEST(AdaptiveStep, StaysInItsBoundsAndShortensWhereTheWheelMeetsTheDip) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("gauss_seidel", 0.01);
  const auto dir = run("adaptive_gs_bounds", s);
  std::vector<double> ends;
  const std::vector<double> steps = macro_steps(dir, ends);
  ASSERT_GT(steps.size(), 10u);
  double before = 0.0, at_dip = 1.0, shortest = 1.0, longest = 0.0;
  double t = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    t += steps[k];
    EXPECT_NEAR(ends[k], t, 1e-12);  // the recorded step is the step that ended there
    shortest = std::min(shortest, steps[k]);
    longest = std::max(longest, steps[k]);
    if (k + 1 < steps.size()) {
      EXPECT_GE(steps[k], kMinStep * (1 - 1e-9));
      EXPECT_LE(steps[k], kMaxStep * (1 + 1e-9));
      EXPECT_NEAR(steps[k] / kMinStep, std::round(steps[k] / kMinStep), 1e-6);
    }
    if (ends[k] < 0.009) before = std::max(before, steps[k]);
    if (ends[k] > 0.011 && ends[k] < 0.02) at_dip = std::min(at_dip, steps[k]);
  }
  EXPECT_NEAR(ends.back(), kEnd, 1e-12);
  std::cout << "[ measured ] " << steps.size() << " steps; longest before the dip " << before
            << " s, shortest after it " << at_dip << " s\n";
  EXPECT_GT(before, 4.0 * at_dip);  // measured 1 ms and 0.15 ms
  const nlohmann::json summary = read_json(dir / "summary.json");
  const nlohmann::json& recorded = summary["coupling"]["macro_step_s"];
  EXPECT_NEAR(recorded["shortest"].get<double>(), shortest, 1e-12);  // CSV: 12 digits
  EXPECT_NEAR(recorded["longest"].get<double>(), longest, 1e-12);
}

/// A run's error against a reference: displacements (relative_error) and footprint PPV (the
/// largest difference over the footprints, relative to the reference's largest PPV); its cost:
/// the steps, those taken again above the tolerance (each a track and a soil solve too) and
/// jacobi's extra soil advances probing its held force's cost (each counted as a whole step,
/// though a soil-only advance costs less).
struct RunError {
  double displacement = 0.0, ppv = 0.0;
  std::size_t steps = 0, retaken = 0, probes = 0;
  double cost() const { return static_cast<double>(steps + retaken + probes); }
};

RunError run_error(const std::filesystem::path& dir, const std::filesystem::path& reference,
                   std::size_t retaken = 0) {
  RunError e;
  e.displacement = relative_error(csv(dir / "footprint_displacement.csv"),
                                  csv(reference / "footprint_displacement.csv"));
  const auto ppv = read_json(dir / "summary.json")["peak_footprint_velocity_m_s"];
  const auto ref = read_json(reference / "summary.json")["peak_footprint_velocity_m_s"];
  double largest = 0.0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    e.ppv = std::max(e.ppv, std::abs(ppv[i].get<double>() - ref[i].get<double>()));
    largest = std::max(largest, ref[i].get<double>());
  }
  e.ppv /= largest;
  std::vector<double> ends;
  e.steps = macro_steps(dir, ends).size();
  e.retaken = retaken;
  return e;
}

/// The steps fixed steps need for `error` in the measure `of`: log-log between the two fixed
/// runs (coarse to fine) that bracket it; below the finest one's error, at least the finest's
/// steps; 0 when even the coarsest is more accurate.
double fixed_steps_at(const std::vector<RunError>& fixed, double RunError::*of, double error) {
  if (error <= fixed.back().*of) return fixed.back().cost();
  for (std::size_t k = 0; k + 1 < fixed.size(); ++k) {
    const RunError &a = fixed[k], &b = fixed[k + 1];
    if (a.*of >= error && b.*of <= error) {
      const double slope = std::log(b.cost() / a.cost()) / std::log(b.*of / a.*of);
      return a.cost() * std::pow(error / (a.*of), slope);
    }
  }
  return 0.0;
}

/// Fixed steps H [s] on a scenario (`make`), against `reference`, printed.
template <typename Make>
std::vector<RunError> fixed_runs(const std::string& name, Make make,
                                 const std::vector<double>& steps,
                                 const std::filesystem::path& reference) {
  std::vector<RunError> fixed;
  for (double H : steps) {
    const auto dir = run(name + std::to_string(std::lround(H * 1e6)), make(H));
    fixed.push_back(run_error(dir, reference));
    std::cout << "[ measured ] fixed " << H << " s: " << fixed.back().steps
              << " steps, displacement error " << fixed.back().displacement << ", PPV error "
              << fixed.back().ppv << "\n";
  }
  return fixed;
}

/// The scenario with a fixed-step coupler of this type (its default parameters).
nlohmann::json fixed_coupler(nlohmann::json s, const std::string& type = "gauss_seidel") {
  s["coupling"] = {{"type", type}, {"params", nlohmann::json::object()}};
  return s;
}

TEST(AdaptiveStep, EndingInsideTheDipItStillCostsLessThanFixedSteps) {
  // Two thirds of this run are the dip, where the step must be short whatever the controller:
  // steps of 1 ms before the dip and 0.25 ms from it (set by hand) cost 0.84 of fixed steps at
  // equal PPV error (docs/couplers.md), so only the displacement is claimed here.
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("gauss_seidel", 0.01);
  std::size_t retaken = 0;
  const auto dir = run_counting_retakes("adaptive_gs_cost", s, retaken);
  const RunError adaptive = run_error(dir, reference_dir(), retaken);
  const std::vector<RunError> fixed = fixed_runs(
      "adaptive_gs_fixed_", [](double H) { return fixed_coupler(dip(H)); },
      {2.5e-4, 1.5e-4, 1e-4, 5e-5}, reference_dir());
  const double equal = fixed_steps_at(fixed, &RunError::displacement, adaptive.displacement);
  ASSERT_GT(equal, 0.0) << "the fixed steps do not bracket the adaptive error "
                        << adaptive.displacement;
  const double ratio = adaptive.cost() / equal;
  std::cout << "[ measured ] adaptive (tolerance 0.01): " << adaptive.steps << " steps + "
            << adaptive.retaken << " taken again, displacement error " << adaptive.displacement
            << ", PPV error " << adaptive.ppv
            << "; fixed steps at that displacement error: " << equal << "; ratio " << ratio << "\n";
  // Measured 0.82 (164 + 15 against 219); the controller of SDK 1.3 before the step-change
  // limit: 0.97 (145 + 67 against 218).
  EXPECT_LT(ratio, 0.9);
}

TEST(AdaptiveStep, OnThePapersDipCaseItsStepsShrinkAtTheDip) {
  for (const std::string coupler : {"gauss_seidel", "jacobi"}) {
    nlohmann::json s = paper_dip(1e-3);
    s["coupling"] = adaptive_coupler(coupler, 0.1);
    std::vector<double> ends;
    const std::vector<double> steps =
        macro_steps(run("adaptive_paper_shrinks_" + coupler, s), ends);
    double before = 0.0, at_dip = 1.0;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      if (ends[k] < 0.14) before = std::max(before, steps[k]);
      if (ends[k] > 0.148 && ends[k] < 0.175) at_dip = std::min(at_dip, steps[k]);
    }
    std::cout << "[ measured ] " << coupler << ": " << steps.size()
              << " steps; longest before the dip " << before << " s, shortest at it " << at_dip
              << " s\n";
    // Measured 2 ms and 0.15 ms (gauss_seidel), 1 ms and 0.05 ms (jacobi).
    EXPECT_GT(before, 4.0 * at_dip) << coupler;
  }
}

/// A soil of the paper and a coupler, with the most the adaptive step may cost against fixed
/// steps at equal PPV and at equal displacement error.
struct PaperCase {
  const char* label;
  const char* file;
  const char* coupler;
  double ppv_bound, displacement_bound;
};

void PrintTo(const PaperCase& c, std::ostream* os) {
  *os << c.label;
}

class AdaptiveStepOnThePapersDipCase : public ::testing::TestWithParam<PaperCase> {};

TEST_P(AdaptiveStepOnThePapersDipCase, CostsLessThanFixedStepsAtEqualPpvAndDisplacementError) {
  // (eight runs of the dip case at five fixed steps and two tolerances, 26 s each case under
  // the sanitizers: the adaptive paths run there in OnThePapersDipCaseItsStepsShrinkAtTheDip)
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  const PaperCase c = GetParam();
  const std::string name = std::string("adaptive_paper_") + c.file + "_" + c.coupler + "_";
  const auto reference = monolithic(name + "reference", paper_dip(1e-3, c.file));
  const std::vector<RunError> fixed = fixed_runs(
      name + "fixed_", [&](double H) { return fixed_coupler(paper_dip(H, c.file), c.coupler); },
      {1e-3, 5e-4, 2.5e-4, 1e-4, 5e-5}, reference);
  std::vector<RunError> adaptive;
  for (double tolerance : {0.1, 0.04}) {
    nlohmann::json s = paper_dip(1e-3, c.file);
    s["coupling"] = adaptive_coupler(c.coupler, tolerance);
    std::size_t retaken = 0, probes = 0;
    const auto dir = run_counting_retakes(name + std::to_string(std::lround(1e3 * tolerance)), s,
                                          retaken, &probes);
    RunError e = run_error(dir, reference, retaken);
    e.probes = probes;
    adaptive.push_back(e);
    for (const auto& [measure, of, bound] :
         {std::tuple{"PPV", &RunError::ppv, c.ppv_bound},
          std::tuple{"displacement", &RunError::displacement, c.displacement_bound}}) {
      const double equal = fixed_steps_at(fixed, of, e.*of);
      std::cout << "[ measured ] adaptive (tolerance " << tolerance << "): " << e.steps
                << " steps + " << e.retaken << " taken again + " << e.probes << " probes, "
                << measure << " error " << e.*of << "; fixed steps at that error: " << equal
                << "; ratio " << e.cost() / equal << "\n";
      EXPECT_GT(equal, 0.0) << "fixed steps of 1 ms are more accurate than the adaptive " << measure
                            << " error " << e.*of;
      EXPECT_LE(e.cost() / equal, bound) << measure << ", tolerance " << tolerance;
    }
  }
  // Its errors fall with the tolerance.
  EXPECT_GT(adaptive[0].displacement / adaptive[1].displacement, 1.3);
  EXPECT_GT(adaptive[0].ppv, adaptive[1].ppv);
}

// Measured (docs/couplers.md, adaptive macro steps), tolerance 0.1 and 0.04: PPV 0.41 and
// 0.25, displacement 0.35 and 0.34 (medium soil, Winkler); 0.35 and 0.21, 0.45 and 0.41
// (medium, CLM); 0.30 and 0.29, 0.35 and 0.30 (stiff, CLM). jacobi, its soil's held force
// counted in the soil's velocity (its probes counted as steps): PPV 0.54 and 0.35 (before:
// 0.83 and 0.91), displacement 0.97 and 0.53 (before: 0.70 and 0.39): at tolerance 0.1 it
// spends twice fixed steps' count through the dip, where the PPV needs it, while the
// displacement error is set after the dip, where it takes steps of up to 2 ms; so it is held
// to fixed steps' cost at equal displacement error.
INSTANTIATE_TEST_SUITE_P(
    Soils, AdaptiveStepOnThePapersDipCase,
    ::testing::Values(
        PaperCase{"GaussSeidelMediumWinkler", "medium_soil_winkler", "gauss_seidel", 0.7, 0.7},
        PaperCase{"GaussSeidelMediumClm", "medium_soil_gauss_seidel", "gauss_seidel", 0.7, 0.7},
        PaperCase{"GaussSeidelStiffClm", "stiff_soil_gauss_seidel", "gauss_seidel", 0.7, 0.7},
        PaperCase{"JacobiMediumWinkler", "medium_soil_winkler", "jacobi", 0.7, 1.0}),
    [](const ::testing::TestParamInfo<PaperCase>& param) {
      return std::string(param.param.label);
    });

TEST(AdaptiveStep, JacobiAdaptsToo) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("jacobi", 0.05);
  const auto dir = run("adaptive_jacobi", s);
  std::vector<double> ends;
  const std::vector<double> steps = macro_steps(dir, ends);
  const double error = relative_error(csv(dir / "footprint_displacement.csv"),
                                      csv(reference_dir() / "footprint_displacement.csv"));
  std::cout << "[ measured ] jacobi: " << steps.size() << " steps, error " << error << "\n";
  EXPECT_NEAR(ends.back(), kEnd, 1e-12);
  const double shortest = *std::min_element(steps.begin(), steps.end() - 1);
  EXPECT_LT(shortest, 0.25 * kMaxStep);
  EXPECT_GT(*std::max_element(steps.begin(), steps.end()), 2.0 * shortest);  // it does vary
  // Of the order of gauss_seidel's at a tolerance of 0.01 (0.012); measured 0.011.
  EXPECT_LT(error, 0.05);
}

TEST(AdaptiveStep, InvertedBoundsAreRefusedAtValidate) {
  nlohmann::json s = dip(1e-3);
  s["coupling"] = adaptive_coupler("gauss_seidel", 0.05);
  s["coupling"]["params"]["adaptive"]["min_step"] = 1e-3;
  s["coupling"]["params"]["adaptive"]["max_step"] = 1e-4;
  const auto dir = scratch_directory("adaptive_inverted");
  const CliResult r = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("/coupling"));
  EXPECT_THAT(r.output, HasSubstr("min_step 0.001 s is longer than max_step 0.0001 s"));
  EXPECT_THAT(r.output, HasSubstr("give min_step <= max_step"));
}

}  // namespace
}  // namespace rumble::testing
