// Soil field snapshots (ABI 1.1 write_fields) at the cadence of /outputs/fields: the soil writes
// each .vtu, the engine names them and keeps soil.pvd, the ParaView index, valid after each one.
// picky_soil writes its footprint displacements; 0.05 s at an interval of 0.01 s is 6 snapshots
// (t = 0 included).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "boundary_support.hpp"

namespace rumble::testing {
namespace {

TEST(Fields, SnapshotsAtTheIntervalWithAParaViewIndex) {
  nlohmann::json s = fixture_scenario({{"type", "picky_soil"}}, {{"type", "gauss_seidel"}});
  s["outputs"]["fields"] = {{"interval", 0.01}};
  CliResult r;
  const auto dir = run_in("fields_snapshots", s, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string index = file_text(dir / "soil.pvd");
  const std::regex dataset(R"re(<DataSet timestep="([^"]+)" group="" part="0" file="([^"]+)"/>)re");
  std::vector<double> times;
  for (auto it = std::sregex_iterator(index.begin(), index.end(), dataset);
       it != std::sregex_iterator(); ++it) {
    times.push_back(std::stod((*it)[1].str()));
    const std::string vtu = file_text(dir / (*it)[2].str());
    EXPECT_NE(vtu.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos) << (*it)[2];
  }
  ASSERT_EQ(times.size(), 6u) << index;
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(times[k], 0.01 * k, 1e-12);
  const auto summary = read_json(dir / "summary.json");
  EXPECT_EQ(summary["field_snapshots"], 6);
}

TEST(Fields, ASoilWithoutFieldOutputIsAWarningOnly) {
  nlohmann::json s = fixture_scenario({{"type", "forgetful_soil"}}, {{"type", "gauss_seidel"}});
  s["outputs"]["fields"] = {{"interval", 0.01}};
  CliResult r;
  const auto dir = run_in("fields_not_offered", s, r);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("soil type \"forgetful_soil\" writes no field output"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "soil.pvd"));
}

// A rerun of the same scenario file removes what the run before listed: here its snapshots, their
// index and the soil's own finalized.json, none of which the rerun (a soil without fields)
// writes again.
TEST(Fields, ARerunWithoutFieldsLeavesNoStaleSnapshots) {
  namespace fs = std::filesystem;
  nlohmann::json s = fixture_scenario({{"type", "picky_soil"}}, {{"type", "gauss_seidel"}});
  s["outputs"]["fields"] = {{"interval", 0.01}};
  const auto dir = scratch_directory("fields_rerun");
  const auto results = dir / "results";
  const auto path = write_scenario(dir, s);
  CliResult r = run_rumble({"run", path.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(results / "soil.pvd"));
  ASSERT_TRUE(fs::exists(results / "fields" / "soil_000005.vtu"));
  ASSERT_TRUE(fs::exists(results / "finalized.json"));
  s["soil"] = {{"type", "forgetful_soil"}};
  s["outputs"].erase("fields");
  write_scenario(dir, s);
  r = run_rumble({"run", path.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(results / "soil.pvd"));
  EXPECT_FALSE(fs::exists(results / "fields"));
  EXPECT_FALSE(fs::exists(results / "finalized.json"));
  EXPECT_EQ(csv_rows(results / "contact.csv"), 51u);
}

// The soil writes each snapshot itself, at a path the engine has cleared: a link planted at a
// snapshot's name, or at fields/ itself, is replaced, and its target is never written.
TEST(Fields, SnapshotsNeverGoThroughALink) {
  namespace fs = std::filesystem;
  nlohmann::json s = fixture_scenario({{"type", "picky_soil"}}, {{"type", "gauss_seidel"}});
  s["outputs"]["fields"] = {{"interval", 0.01}};
  const auto dir = scratch_directory("fields_links");
  std::ofstream(dir / "precious.txt") << "keep me";
  fs::create_directories(dir / "results" / "fields");
  fs::create_symlink(dir / "precious.txt", dir / "results" / "fields" / "soil_000000.vtu");
  // --overwrite: the links are no results of a run before (no manifest lists them).
  CliResult r =
      run_rumble({"run", write_scenario(dir, s).string(), "--no-progress", "--overwrite"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file_text(dir / "precious.txt"), "keep me");
  EXPECT_FALSE(fs::is_symlink(dir / "results" / "fields" / "soil_000000.vtu"));
  EXPECT_NE(file_text(dir / "results" / "fields" / "soil_000000.vtu").find("<VTKFile"),
            std::string::npos);

  const auto other = scratch_directory("fields_directory_link");
  fs::create_directories(other / "elsewhere");
  fs::create_directories(other / "results");
  fs::create_symlink(other / "elsewhere", other / "results" / "fields");
  r = run_rumble({"run", write_scenario(other, s).string(), "--no-progress", "--overwrite"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::is_empty(other / "elsewhere"));
  EXPECT_FALSE(fs::is_symlink(other / "results" / "fields"));
  EXPECT_TRUE(fs::exists(other / "results" / "fields" / "soil_000005.vtu"));
}

}  // namespace
}  // namespace rumble::testing
