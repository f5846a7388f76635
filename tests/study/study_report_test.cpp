// The study report: a small FEM study (two-step against Gauss-Seidel, receivers at 2.5 m and
// 5 m) ends with report.html, which a headless browser (chromium-headless-shell, installed by
// tools/install_dependencies.sh) renders with every image decoded, and which lists every run in
// its PPV and diagnostics tables with the figures also written as PNG and SVG. The shipped
// quick study of the seed paper is valid (every run checked by --dry-run).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "post/time_series.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr const char* kBrowser = "/usr/bin/chromium-headless-shell";

/// The page's DOM after load, as the browser serializes it.
std::string rendered_dom(const fs::path& page) {
  const fs::path out = page.parent_path() / "dom.html";
  const std::string command = std::string(kBrowser) +
                              " --no-sandbox --disable-gpu --allow-file-access-from-files "
                              "--virtual-time-budget=5000 --dump-dom 'file://" +
                              page.string() + "' > '" + out.string() + "' 2>/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return file_text(out);
}

/// Receivers of a run's post/ppv.csv with more than a fifth of their vertical energy above the
/// band their mesh resolves (tools/study_report.py's UNRESOLVED_SHARE).
int mostly_unresolved_receivers(const fs::path& ppv_csv) {
  std::ifstream in(ppv_csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = post::split_csv_line(line);
  const auto column = std::find(header.begin(), header.end(), "energy_z above f_resolved [-]");
  if (column == header.end()) return 0;
  int count = 0;
  while (std::getline(in, line)) {
    const std::string share =
        post::split_csv_line(line).at(static_cast<std::size_t>(column - header.begin()));
    if (!share.empty() && std::stod(share) > 0.2) ++count;
  }
  return count;
}

TEST(StudyReport, RendersInABrowserWithEveryImageAndEveryRun) {
  ASSERT_EQ(::access(kBrowser, X_OK), 0)
      << kBrowser << " is missing: tools/install_dependencies.sh installs chromium-headless-shell";
  const auto dir = scratch_directory("study_report");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json base = small_fem_scenario();
  base["time"]["end"] = 0.05;
  base["outputs"]["receivers"] = {2.5, 5.0};
  write_scenario(dir, base);
  const nlohmann::json clm = {{"type", "clm"},
                              {"params", {{"E", 750e6}, {"nu", 0.3}, {"rho", 1800.0}}}};
  const nlohmann::json study = {
      {"study_version", 1},
      {"name", "report test"},
      {"scenario", "scenario.json"},
      {"output", "out"},
      {"runs",
       {{{"name", "two_step"},
         {"set",
          {{"/coupling",
            {{"type", "two_step"},
             {"params", nlohmann::json::object()},
             {"participants", {{"reduced_soil", clm}}}}}}}},
        {{"name", "gs"}, {"set", {{"/coupling/type", "gauss_seidel"}}}}}}};
  std::ofstream(dir / "report.study.json") << study.dump(2);
  const CliResult r = run_rumble({"study", (dir / "report.study.json").string(), "--jobs", "1"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("study report: " + (dir / "out" / "report.html").string()));

  const fs::path page = dir / "out" / "report.html";
  const std::string dom = rendered_dom(page);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-images-loaded=\"(\\d+)/(\\d+)\"")))
      << "the page did not finish loading in the browser";
  EXPECT_EQ(m[1], m[2]) << "images that did not decode";
  // PPV against distance, two scalograms, contact force, the cut.
  EXPECT_GE(std::stoi(m[2]), 5);
  for (const char* run : {">two_step<", ">gs<"}) EXPECT_THAT(dom, HasSubstr(run));
  EXPECT_THAT(dom, HasSubstr("All 2 runs completed."));
  EXPECT_THAT(dom, HasSubstr("Vertical PPV [mm/s] by distance from the track [m]"));
  EXPECT_THAT(dom, HasSubstr("footprint_displacement mismatch"));
  // The coupling error with the scheme's order (docs/couplers.md), in the table and the figure.
  EXPECT_THAT(dom, HasSubstr("predictor residual (coupling error, the scheme's order)"));
  EXPECT_THAT(dom, HasSubstr("energy, residual and coupling error"));
  // No raw number of a record with a fifth of its energy above its band without a mark: the PPV
  // table's cell and the indicators' six raw values (PPV_z, PPV_3c, f_dom, KB, DIN, BS) of each
  // such receiver are shaded and starred (issue 29; this coarse mesh has such receivers at 5 m).
  const int unresolved =
      mostly_unresolved_receivers(dir / "out" / "two_step" / "post" / "ppv.csv") +
      mostly_unresolved_receivers(dir / "out" / "gs" / "post" / "ppv.csv");
  EXPECT_GT(unresolved, 0);
  const std::string page_text = file_text(page);
  std::size_t marked = 0;
  for (std::size_t at = page_text.find("class='unresolved'"); at != std::string::npos;
       at = page_text.find("class='unresolved'", at + 1))
    ++marked;
  EXPECT_EQ(marked, 7u * static_cast<std::size_t>(unresolved));
  for (const char* f : {"ppv_vs_distance", "contact_force", "interface"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / "figures" / (std::string(f) + ".png"))) << f;
    EXPECT_TRUE(fs::exists(dir / "out" / "figures" / (std::string(f) + ".svg"))) << f;
  }
}

// A run stopped as diverged is in the report with what it recorded, marked with when it stopped
// (the seed paper shows its unstable Jacobi run so, Figure 4): in the PPV table and figure.
TEST(StudyReport, ADivergedRunIsShownUpToWhereItGot) {
  const auto dir = scratch_directory("study_report_diverged");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json base = small_fem_scenario();
  base["time"]["end"] = 0.03;
  base["outputs"]["receivers"] = {2.5, 5.0};
  write_scenario(dir, base);
  // A 5 mm dip under the starting wheel and a bound of 2.01 x the static settlement stop "stops"
  // at its impact (tests/cli/cli_post_test.cpp).
  const nlohmann::json study = {
      {"study_version", 1},
      {"scenario", "scenario.json"},
      {"output", "out"},
      {"runs",
       {{{"name", "gs"}},
        {{"name", "stops"},
         {"set",
          {{"/track/unevenness",
            {{"type", "dip"}, {"position", 3.2}, {"length", 0.3}, {"depth", 5e-3}}},
           {"/coupling/divergence", {{"displacement_factor", 2.01}}}}}}}}};
  std::ofstream(dir / "diverged.study.json") << study.dump(2);
  const CliResult r = run_rumble({"study", (dir / "diverged.study.json").string(), "--jobs", "1"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  const std::string page = file_text(dir / "out" / "report.html");
  EXPECT_THAT(page, HasSubstr("stops (failed at 0.01"));  // the PPV table's column
  EXPECT_TRUE(fs::exists(dir / "out" / "stops" / "post" / "ppv.csv"));
  EXPECT_TRUE(fs::exists(dir / "out" / "figures" / "ppv_vs_distance.png"));
}

// The quick study (the README's main job) here; the full paper study meshes a soft soil of
// 3.7e5 DOFs to validate, so its check is in the validation label (tests/scenarios).
TEST(StudyReport, TheQuickPaperStudyIsValid) {
  // A copy in a scratch folder: the check does not depend on results a user has in the tree.
  const fs::path source = fs::path(RUMBLE_TEST_SOURCE_DIR) / "scenarios/paper/study";
  const auto dir = scratch_directory("paper_quick_study");
  for (const char* f : {"quick.study.json", "track_on_fem_soil.json"})
    fs::copy_file(source / f, dir / f, fs::copy_options::overwrite_existing);
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const CliResult r = run_rumble({"study", (dir / "quick.study.json").string(), "--dry-run"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("medium-two_step: would run"));
  EXPECT_THAT(r.output, HasSubstr("medium-gs: would run"));
  EXPECT_THAT(r.output, Not(HasSubstr("not valid:")));
}

}  // namespace
}  // namespace rumble::testing
