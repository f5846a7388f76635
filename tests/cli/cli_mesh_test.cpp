// `rumble mesh`: the soil built on the scenario's footprints without a run, its mesh written for
// ParaView, the second time from the mesh cache; a soil without field output says so.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sched.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(CliMesh, WritesTheMeshAndReusesItFromTheCache) {
  const auto dir = scratch_directory("mesh_fem");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const auto path = write_scenario(dir, small_fem_scenario());
  const CliResult first = run_rumble({"mesh", path.string()});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_THAT(first.output, HasSubstr("tetrahedra"));
  EXPECT_THAT(first.output, HasSubstr("stable step"));
  EXPECT_THAT(first.output, HasSubstr("wrote " + (dir / "results" / "mesh.vtu").string()));
  EXPECT_THAT(file_text(dir / "results" / "mesh.vtu"),
              HasSubstr("<VTKFile type=\"UnstructuredGrid\""));
  const CliResult second =
      run_rumble({"mesh", path.string(), "--output", (dir / "again").string()});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_THAT(second.output, HasSubstr("fem: mesh from the cache " + (dir / "cache").string()));
  EXPECT_EQ(file_text(dir / "again" / "mesh.vtu"), file_text(dir / "results" / "mesh.vtu"));
  ::unsetenv("RUMBLE_MESH_CACHE");
}

// `rumble mesh` writes beside a scenario's results by default: a run then leaves it alone (the
// results directory's manifest refuses unknown files, docs/scenario.md).
TEST(CliMesh, ARunLeavesTheMeshBesideItsResults) {
  const auto dir = scratch_directory("mesh_then_run");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.01;
  const auto path = write_scenario(dir, s).string();
  ASSERT_EQ(run_rumble({"mesh", path}).exit_code, 0);
  const CliResult run = run_rumble({"run", path, "--no-progress", "--no-plots"});
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run_rumble({"run", path, "--no-progress", "--no-plots"}).exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "results" / "mesh.vtu"));
  ::unsetenv("RUMBLE_MESH_CACHE");
}

// The soil gets the cores the process may use (its CPU affinity, as taskset sets it), not the
// machine's: more threads than cores make the FEM step's barriers wait on a descheduled thread.
TEST(CliMesh, TheSoilGetsTheCoresTheProcessMayUse) {
  const auto dir = scratch_directory("mesh_affinity");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.002;
  const auto path = write_scenario(dir, s).string();
  cpu_set_t saved, one;
  ASSERT_EQ(sched_getaffinity(0, sizeof saved, &saved), 0);
  CPU_ZERO(&one);
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &saved)) {
      CPU_SET(cpu, &one);
      break;
    }
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);  // inherited by the rumble it starts
  const CliResult r = run_rumble({"run", path, "--no-progress", "--no-plots"});
  sched_setaffinity(0, sizeof saved, &saved);
  ::unsetenv("RUMBLE_MESH_CACHE");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("per macro step of 0.001 s, 1 thread(s)"));
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Validation builds the soil on the footprints to check it; run, mesh, soil-frf, calibrate (and
// stability, not timed here: its analysis takes seconds) take that soil instead of building it
// again (a FEM soil of 1e6 DOFs costs about 21 s
// and 6 GB to build). The FEM soil reports "ready in" once per build.
TEST(CliMesh, TheSoilIsBuiltOncePerCommand) {
  const auto dir = scratch_directory("mesh_built_once");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  nlohmann::json s = small_fem_scenario();
  s["time"]["end"] = 0.002;
  const auto path = write_scenario(dir, s).string();
  const CliResult mesh = run_rumble({"mesh", path});
  const CliResult run = run_rumble({"run", path, "--no-progress", "--no-plots"});
  const CliResult frf = run_rumble({"soil-frf", path, "--points", "2", "--no-plot"});
  const CliResult fit = run_rumble({"calibrate", path, "--model", "winkler", "--params",
                                    R"({"k": 1e8, "c": 1e5})", "--points", "3", "--fmax", "20"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  for (const CliResult* r : {&mesh, &run, &frf, &fit}) {
    ASSERT_EQ(r->exit_code, 0) << r->output;
    EXPECT_EQ(occurrences(r->output, "ready in"), 1u) << r->output;
  }
}

// `rumble mesh --set` changes the scenario before it is checked, as `rumble run --set` does.
TEST(CliMesh, SetChangesTheScenarioFirst) {
  const auto dir = scratch_directory("mesh_set");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const auto path = write_scenario(dir, small_fem_scenario()).string();
  const CliResult refused = run_rumble({"mesh", path, "--set", "/soil/params/nu=0.5"});
  const CliResult coarser = run_rumble({"mesh", path, "--set", "/soil/params/mesh/f_max=20"});
  ::unsetenv("RUMBLE_MESH_CACHE");
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("/soil/params/nu"));
  EXPECT_THAT(refused.output, HasSubstr("(set by --set)"));
  ASSERT_EQ(coarser.exit_code, 0) << coarser.output;
  EXPECT_THAT(coarser.output, HasSubstr("20 Hz at 2.5 m"));  // the 40 Hz mesh resolves more
}

// mesh.refine keeps the coarse tetrahedra's shapes: where gmsh's coarse size near the track is
// wider than a footprint, the flattened tetrahedra along its edges set the stable step, and the
// log says so (docs/fem-soil.md §2); at the rule's sizes nothing is said.
TEST(CliMesh, RefiningAMeshCoarserThanTheFootprintsWarns) {
  const auto dir = scratch_directory("mesh_refine_warns");
  ::setenv("RUMBLE_MESH_CACHE", (dir / "cache").c_str(), 1);
  const auto path = write_scenario(dir, small_fem_scenario()).string();
  const CliResult plain = run_rumble({"mesh", path});
  const CliResult refined = run_rumble(
      {"mesh", path, "--set", "/soil/params/mesh/refine=1", "--output", (dir / "r").string()});
  ::unsetenv("RUMBLE_MESH_CACHE");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_THAT(plain.output, Not(HasSubstr("params/mesh/refine")));
  ASSERT_EQ(refined.exit_code, 0) << refined.output;
  EXPECT_THAT(refined.output, HasSubstr("refined 1 times (mesh.refine)"));
  EXPECT_THAT(refined.output, HasSubstr("params/mesh/refine 1: gmsh meshed at"));
  EXPECT_THAT(refined.output, HasSubstr("wider than the narrowest footprint (0.26 m)"));
}

/// What `dir` holds, every level, as paths relative to it ("" when empty).
std::string listing(const std::filesystem::path& dir) {
  std::string out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    out += e.path().lexically_relative(dir).string() + "\n";
  return out;
}

// gmsh reads and writes no file of its own: no options or session file in the home directory,
// no preferences of FLTK (its GUI's toolkit, which wrote ~/.fltk/fltk.org/fltk.prefs), and its
// temporary file there (~/.gmsh-tmp, which it removed) is left alone (docs/fem-soil.md §2).
TEST(CliMesh, GmshWritesNothingIntoTheHomeDirectory) {
  const auto dir = scratch_directory("mesh_home");
  std::filesystem::create_directories(dir / "home");
  RunSetup setup;
  setup.environment = {{"HOME", (dir / "home").string()},
                       {"RUMBLE_MESH_CACHE", (dir / "cache").string()}};
  const auto path = write_scenario(dir, small_fem_scenario()).string();
  const CliResult r = run_rumble({"mesh", path}, setup);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(listing(dir / "home"), "");
  // A user's own ~/.gmsh-tmp stays.
  std::ofstream(dir / "home" / ".gmsh-tmp") << "mine\n";
  setup.environment[1].second = "off";  // meshed again
  ASSERT_EQ(run_rumble({"mesh", path, "--output", (dir / "again").string()}, setup).exit_code, 0);
  EXPECT_EQ(listing(dir / "home"), ".gmsh-tmp\n");
  EXPECT_EQ(file_text(dir / "home" / ".gmsh-tmp"), "mine\n");
}

TEST(CliMesh, ASoilWithoutFieldsSaysSo) {
  const auto dir = scratch_directory("mesh_winkler");
  const CliResult r = run_rumble({"mesh", write_scenario(dir, small_scenario()).string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("soil type 'winkler' offers no field output"));
}

TEST(CliMesh, NeedsOneScenario) {
  const CliResult r = run_rumble({"mesh"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("usage: rumble mesh FILE [--output DIR]"));
}

}  // namespace
}  // namespace rumble::testing
