// A user's gmsh mesh file (params/mesh/file): the soil's own mesh written as .msh with its
// physical groups (write_mesh_file) reads back as the same mesh and runs as the generated one,
// through the plugin; a file lacking a group, not matching the track's footprints or layers, or
// holding no tetrahedra is refused with what is wrong, what the file has, and the fix.
#include <gmsh.h>
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "expect_message.hpp"
#include "fem_settings.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/mesh_generator.hpp"
#include "settings_from_params.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

namespace fs = std::filesystem;

/// An empty scratch directory named after the running test.
fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(RUMBLE_TEST_BINARY_DIR) / "fem_mesh_file_tests" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A small two-layer soil (a 1 m named top layer over a stiff half-space) in a 5 m hemisphere:
/// about 1.5k nodes, meshed in well under a second.
nlohmann::json small_layered_soil() {
  return {{"E", 750e6},
          {"nu", 0.3},
          {"rho", 1800.0},
          {"layers",
           {{{"name", "fill"}, {"thickness", 1.0}, {"E", 300e6}, {"nu", 0.3}, {"rho", 1700.0}}}},
          {"mesh", {{"radius", 5.0}, {"f_max", 30.0}, {"near_distance", 1.5}}}};
}

/// The soil's own mesh of params on footprints, written to path as .msh; returns the mesh.
fem::TetMesh write_generated(const nlohmann::json& params,
                             const std::vector<rumble_footprint>& footprints,
                             const fs::path& path) {
  const fem::FemSettings s = rumble::test::settings_from(params);
  const fem::TetMesh mesh = fem::generate_mesh(s, footprints, fem::plan_mesh(s, footprints));
  fem::write_mesh_file(mesh, s, footprints, path.string());
  return mesh;
}

nlohmann::json with_file(nlohmann::json params, const fs::path& path) {
  params["mesh"] = {{"file", path.string()}};
  return params;
}

/// Receiver traces (time, then the 6 values of each probe per sample) over 20 steps of 1 ms
/// after the static state, with the footprint forces swinging by 20 %; and the static
/// footprint displacements.
struct Traces {
  VectorXd u_static;
  std::vector<double> times, values;
};

Traces run(const nlohmann::json& params, const std::vector<rumble_footprint>& footprints,
           const fs::path& results_dir = {}) {
  TestSoil soil("fem", params.dump());
  soil.set_results_dir(results_dir.string());  // "" (the default): no run's, as in validate
  soil.accept_layout(footprints);
  const std::vector<rumble_probe> probes = {{"r1", 0.6, 1.5, 0.0}, {"r2", 0.3, 3.0, 1.0}};
  EXPECT_EQ(soil.api().set_probes(soil.self(), probes.data(), probes.size(), 0.0), RUMBLE_OK);
  const auto n = static_cast<Eigen::Index>(footprints.size());
  Traces r;
  r.u_static = soil.initialize(VectorXd::Constant(n, 5e4));
  for (int k = 0; k < 20; ++k) {
    const double t = 1e-3 * k;
    soil.advance_linear(t, 1e-3, VectorXd::Constant(n, 5e4 * (1.0 + 0.2 * std::sin(300.0 * t))),
                        VectorXd::Constant(n, 5e4 * (1.0 + 0.2 * std::sin(300.0 * (t + 1e-3)))));
    std::vector<double> times(1000), values(1000 * probes.size() * RUMBLE_PROBE_VALUES);
    std::uint64_t got = 0;
    EXPECT_EQ(soil.api().probe_samples(soil.self(), times.data(), values.data(), 1000, &got),
              RUMBLE_OK);
    r.times.insert(r.times.end(), times.begin(), times.begin() + static_cast<std::ptrdiff_t>(got));
    r.values.insert(
        r.values.end(), values.begin(),
        values.begin() + static_cast<std::ptrdiff_t>(got * probes.size() * RUMBLE_PROBE_VALUES));
  }
  return r;
}

TEST(FemMshImport, TheSoilsOwnMeshReadsBackAsTheSameMesh) {
  const fs::path path = scratch() / "soil.msh";
  const auto footprints = sleeper_row(3);
  const fem::TetMesh m = write_generated(small_layered_soil(), footprints, path);
  const fem::FemSettings s = rumble::test::settings_from(small_layered_soil());
  const fem::MeshFile f = fem::load_mesh_file(s, path.string());
  EXPECT_GT(m.tets.size(), 500u);
  EXPECT_LT(fs::file_size(path), 1u << 20);
  EXPECT_EQ(f.mesh.nodes, m.nodes);  // binary .msh: exact
  EXPECT_EQ(f.mesh.tets, m.tets);
  EXPECT_EQ(f.mesh.layer, m.layer);
  EXPECT_EQ(f.mesh.ground, m.ground);
  EXPECT_EQ(f.mesh.truncation, m.truncation);
  ASSERT_TRUE(f.has_footprints);
  ASSERT_EQ(f.footprints.size(), 3u);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_NEAR(f.footprints[j].centre_x(), footprints[j].x, 1e-12);
    EXPECT_NEAR(f.footprints[j].area, 2.6 * 0.26, 1e-9);
  }
  EXPECT_NO_THROW(fem::check_mesh_footprints(f, footprints));
}

TEST(FemMshImport, ARunOnTheImportedMeshIsTheRunOnTheGeneratedMesh) {
  const fs::path path = scratch() / "soil.msh";
  const auto footprints = sleeper_row(3);
  write_generated(small_layered_soil(), footprints, path);
  const Traces generated = run(small_layered_soil(), footprints);
  const Traces imported = run(with_file(small_layered_soil(), path), footprints);
  ASSERT_EQ(generated.u_static.size(), 3);
  for (Eigen::Index j = 0; j < 3; ++j) {
    EXPECT_GT(generated.u_static[j], 1e-5);
    EXPECT_NEAR(imported.u_static[j], generated.u_static[j], 1e-13 * generated.u_static[j]);
  }
  ASSERT_GT(generated.times.size(), 20u);
  ASSERT_EQ(imported.times, generated.times);
  ASSERT_EQ(imported.values.size(), generated.values.size());
  double scale = 0.0;
  for (double v : generated.values) scale = std::max(scale, std::abs(v));
  EXPECT_GT(scale, 0.0);
  for (std::size_t i = 0; i < generated.values.size(); ++i)
    EXPECT_NEAR(imported.values[i], generated.values[i], 1e-12 * scale) << "value " << i;
}

/// path's .msh rewritten to out without the physical group (dim, name), or with it renamed.
void edit_group(const fs::path& path, const fs::path& out, int dim, const std::string& name,
                const std::string& rename = "") {
  fem::GmshSession session(1);
  fem::gmsh_call("edit a physical group", [&] {
    gmsh::open(path.string());
    // Every group taken down, then put back but the one edited.
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    std::vector<std::tuple<int, std::string, std::vector<int>>> kept;
    for (const auto& [d, tag] : groups) {
      std::string n;
      gmsh::model::getPhysicalName(d, tag, n);
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
      if (d == dim && n == name) {
        if (rename.empty()) continue;
        n = rename;
      }
      kept.emplace_back(d, n, entities);
    }
    // (gmsh 4.8 keeps the names of removed groups: drop them too, and number the new ones apart)
    for (const auto& [d, tag] : groups) {
      std::string n;
      gmsh::model::getPhysicalName(d, tag, n);
      if (!n.empty()) gmsh::model::removePhysicalName(n);
    }
    gmsh::model::removePhysicalGroups();
    int tag = 1000;
    for (const auto& [d, n, entities] : kept) {
      gmsh::model::addPhysicalGroup(d, entities, ++tag);
      if (!n.empty()) gmsh::model::setPhysicalName(d, tag, n);
    }
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::option::setNumber("Mesh.SaveAll", 1);  // the elements of a removed group too
    gmsh::write(out.string());
    return 0;
  });
}

/// The message accept_layout gives for params on footprints.
std::string layout_error(const nlohmann::json& params,
                         const std::vector<rumble_footprint>& footprints) {
  TestSoil soil("fem", params.dump());
  std::string message;
  EXPECT_NE(soil.try_accept_layout(footprints, &message), RUMBLE_OK);
  return message;
}

void expect_parts(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST(FemMshImport, MeshExportWritesTheSoilsOwnMeshForMeshFile) {
  // params/mesh/export through the plugin (what `rumble mesh ... --set
  // /soil/params/mesh/export=...` does): the file it writes, given as mesh.file, is the same
  // mesh, so the static footprint displacements agree to round-off (as above: 1e-13).
  const fs::path results = scratch();
  const auto footprints = sleeper_row(3);
  nlohmann::json exporting = small_layered_soil();
  exporting["mesh"]["export"] = "sub/soil.msh";  // its folder is made
  const Traces generated = run(exporting, footprints, results);
  const fs::path path = results / "sub" / "soil.msh";
  ASSERT_TRUE(fs::is_regular_file(path));
  const Traces imported = run(with_file(small_layered_soil(), path), footprints);
  for (Eigen::Index j = 0; j < 3; ++j)
    EXPECT_NEAR(imported.u_static[j], generated.u_static[j], 1e-13 * generated.u_static[j]);
}

// The soil `rumble validate` builds has no results directory: it writes nothing; the soil of a
// run, laid out by its validation before the run gave it one, writes at its first call after
// (issue 30, docs/fem-soil.md §2.1).
TEST(FemMshImport, MeshExportIsWrittenOnlyInARun) {
  const fs::path results = scratch();
  nlohmann::json exporting = small_layered_soil();
  exporting["mesh"]["export"] = "fem_mesh_file_tests_validate.msh";
  TestSoil soil("fem", exporting.dump());
  soil.accept_layout(sleeper_row(3));
  EXPECT_FALSE(fs::exists("fem_mesh_file_tests_validate.msh"));  // (the old scenario_dir ".")
  EXPECT_EQ(soil.last_log("mesh written"), "");
  soil.set_results_dir(results.string());
  soil.initialize(VectorXd::Constant(3, 5e4));
  EXPECT_TRUE(fs::is_regular_file(results / "fem_mesh_file_tests_validate.msh"));
  EXPECT_EQ(soil.last_log("mesh written"),
            "fem: mesh written to " + (results / "fem_mesh_file_tests_validate.msh").string() +
                " (mesh.file reads it back)");
  soil.initialize(VectorXd::Constant(3, 6e4));  // once: a second call writes nothing
}

TEST(FemMshImport, MeshExportStaysInsideTheResultsDirectory) {
  const std::string rule =
      "mesh.export is written inside the run's results directory (outputs.directory, or --output "
      "DIR) and nowhere else: give a path relative to it without '..', e.g. 'soil.msh'";
  for (const auto& [path, why] : std::vector<std::pair<std::string, std::string>>{
           {"/etc/passwd", "it is an absolute path"},
           {"../scenario.json", "it climbs out with \"..\""},
           {"a/../b.msh", "it climbs out with \"..\""}}) {
    nlohmann::json params = small_layered_soil();
    params["mesh"]["export"] = path;
    EXPECT_EQ(creation_error("fem", params.dump()),
              "fem: params/mesh/export: \"" + path + "\": " + why + "; " + rule);
  }
}

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

/// The message accept_layout gives for params exporting to `path` in the results directory `dir`.
std::string export_error(const fs::path& dir, const std::string& path) {
  nlohmann::json params = small_layered_soil();
  params["mesh"]["export"] = path;
  TestSoil soil("fem", params.dump());
  soil.set_results_dir(dir.string());
  std::string message;
  EXPECT_EQ(soil.try_accept_layout(sleeper_row(3), &message), RUMBLE_ERROR);
  return message;
}

// Nothing standing in the results directory is followed, replaced or removed: a link on the way
// or at the name, a file at the name or in the place of a folder.
TEST(FemMshImport, MeshExportIsANewFileThroughRealDirectories) {
  const fs::path dir = scratch();
  fs::create_directories(dir / "results");
  fs::create_directories(dir / "elsewhere");
  const fs::path results = dir / "results";
  fs::create_directory_symlink(dir / "elsewhere", results / "link");
  std::ofstream(dir / "precious.txt") << "keep me\n";
  fs::create_symlink(dir / "precious.txt", results / "to_precious.msh");
  fs::create_symlink(dir / "ghost.msh", results / "dangling.msh");
  std::ofstream(results / "taken.msh") << "mine\n";
  std::ofstream(results / "a_file") << "not a folder\n";
  const std::string through =
      "; the file is written only through real directories inside the results directory, never "
      "through a link: move it away, or give another path";
  const std::string anew =
      "; the file is written as a new one and nothing standing there is replaced (a rerun of the "
      "same scenario removes its own first): move it away, or give another path";
  EXPECT_NE(export_error(results, "link/soil.msh")
                .find("fem: params/mesh/export: \"link/soil.msh\": " + (results / "link").string() +
                      " is a symbolic link (to " + (dir / "elsewhere").string() + ")" + through),
            std::string::npos);
  EXPECT_NE(export_error(results, "a_file/soil.msh")
                .find("fem: params/mesh/export: \"a_file/soil.msh\": " +
                      (results / "a_file").string() + " is a file" + through),
            std::string::npos);
  EXPECT_NE(
      export_error(results, "to_precious.msh")
          .find("fem: params/mesh/export: \"to_precious.msh\": " +
                (results / "to_precious.msh").string() + " is there already (a symbolic link (to " +
                (dir / "precious.txt").string() + "))" + anew),
      std::string::npos);
  EXPECT_NE(export_error(results, "dangling.msh")
                .find((results / "dangling.msh").string() + " is there already (a symbolic link"),
            std::string::npos);
  EXPECT_NE(export_error(results, "taken.msh")
                .find("fem: params/mesh/export: \"taken.msh\": " +
                      (results / "taken.msh").string() + " is there already (a file)" + anew),
            std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "ghost.msh")));
  EXPECT_EQ(first_line(dir / "precious.txt"), "keep me");
  EXPECT_EQ(first_line(results / "taken.msh"), "mine");
  EXPECT_TRUE(fs::is_symlink(results / "to_precious.msh"));
}

TEST(FemMshImport, MeshExportSaysWhenItCannotWrite) {
  nlohmann::json both = with_file(small_layered_soil(), "a.msh");
  both["mesh"]["export"] = "b.msh";
  EXPECT_EQ(creation_error("fem", both.dump()),
            "fem: params/mesh/export: \"b.msh\" would write the soil's own mesh, but mesh.file "
            "\"a.msh\" is the mesh here; drop one of them");
  const fs::path missing = scratch() / "missing";  // a results directory that is not there
  const std::string message = export_error(missing, "soil.msh");
  EXPECT_NE(message.find("fem: params/mesh/export: \"soil.msh\": cannot create " +
                         (missing / "soil.msh").string() +
                         ": No such file or directory; check that its folder can be written, or "
                         "give another path"),
            std::string::npos)
      << message;
}

TEST(FemMshImport, EachMissingGroupIsNamedWithWhatTheFileHasAndTheFix) {
  const fs::path dir = scratch();
  const auto footprints = sleeper_row(3);
  const nlohmann::json soil = small_layered_soil();
  write_generated(soil, footprints, dir / "soil.msh");

  edit_group(dir / "soil.msh", dir / "no_ground.msh", 2, "ground");
  expect_parts(layout_error(with_file(soil, dir / "no_ground.msh"), footprints),
               {"fem: params/mesh/file: '" + (dir / "no_ground.msh").string() + "'",
                "has no physical surface \"ground\" (it has: \"absorbing\", \"footprints\")",
                "name the free surface at z = 0 \"ground\""});

  edit_group(dir / "soil.msh", dir / "no_absorbing.msh", 2, "absorbing");
  expect_parts(layout_error(with_file(soil, dir / "no_absorbing.msh"), footprints),
               {"has no physical surface \"absorbing\" (it has: \"footprints\", \"ground\")",
                "the truncation surface \"absorbing\""});

  edit_group(dir / "soil.msh", dir / "no_footprints.msh", 2, "footprints");
  expect_parts(layout_error(with_file(soil, dir / "no_footprints.msh"), footprints),
               {"has no physical surface \"footprints\" (it has: \"absorbing\", \"ground\")",
                "the track has 3 footprint(s), 2.6 m x 0.26 m (across x along), centred at x = 0 "
                ".. 1.2 m every 0.6 m, y = 0 m",
                "put them in a physical surface \"footprints\""});

  edit_group(dir / "soil.msh", dir / "no_layer.msh", 3, "fill");
  expect_parts(layout_error(with_file(soil, dir / "no_layer.msh"), footprints),
               {"tetrahedra are in no physical volume named for a layer",
                "\"fill\", \"layer_0\", \"half_space\", \"layer_1\""});

  edit_group(dir / "soil.msh", dir / "wrong_layer.msh", 3, "fill", "clay");
  expect_parts(layout_error(with_file(soil, dir / "wrong_layer.msh"), footprints),
               {"has the physical volume(s) \"clay\", which name no layer of params/layers",
                "name each volume for its layer: \"fill\", \"layer_0\", \"half_space\""});
}

TEST(FemMshImport, FootprintsNotTheTracksAreRefused) {
  const fs::path dir = scratch();
  const auto footprints = sleeper_row(3);
  const nlohmann::json soil = with_file(small_layered_soil(), dir / "soil.msh");
  write_generated(small_layered_soil(), footprints, dir / "soil.msh");
  expect_parts(layout_error(soil, sleeper_row(2)),
               {"fem: the track's footprints do not fit the mesh of params/mesh/file '",
                "has 3 footprint rectangle(s) in its physical surface \"footprints\" (centred at "
                "x = 0 .. 1.2 m); the track has 2 footprint(s)",
                "mesh one rectangle per footprint"});
  auto moved = footprints;
  moved[1].x += 0.05;  // 5 cm: beyond 2 % of the 0.26 m width
  expect_parts(layout_error(soil, moved),
               {"footprint 1 of the track (centre x 0.65 m, y 0 m, 2.6 m x 0.26 m) has no "
                "rectangle of the physical surface \"footprints\" within 0.0052 m; the nearest is "
                "centred at x 0.6 m",
                "place the mesh's footprints at the track's, or change /track/sleepers"});
  moved[1].x = 0.6 + 0.004;  // within the tolerance: accepted (the area check passes too)
  TestSoil within("fem", soil.dump());
  std::string message;
  EXPECT_EQ(within.try_accept_layout(moved, &message), RUMBLE_OK) << message;
}

TEST(FemMshImport, FilesThatAreNoTetrahedralMeshAreRefused) {
  const fs::path dir = scratch();
  const auto footprints = sleeper_row(1);
  // One hexahedron with the groups: no tetrahedra.
  {
    fem::GmshSession session(1);
    namespace gm = gmsh::model;
    const int volume = gm::addDiscreteEntity(3);
    gm::mesh::addNodes(3, volume, {1, 2, 3, 4, 5, 6, 7, 8},
                       {-2, -2, -2, 2, -2, -2, 2, 2, -2, -2, 2, -2,  //
                        -2, -2, 0,  2, -2, 0,  2, 2, 0,  -2, 2, 0});
    gm::mesh::addElementsByType(volume, 5, {1}, {1, 2, 3, 4, 5, 6, 7, 8});
    const int top = gm::addDiscreteEntity(2), bottom = gm::addDiscreteEntity(2);
    gm::mesh::addElementsByType(top, 2, {2, 3}, {5, 6, 7, 5, 7, 8});
    gm::mesh::addElementsByType(bottom, 2, {4, 5}, {1, 2, 3, 1, 3, 4});
    gm::setPhysicalName(2, gm::addPhysicalGroup(2, {top}), "ground");
    gm::setPhysicalName(2, gm::addPhysicalGroup(2, {bottom}), "absorbing");
    gm::addPhysicalGroup(3, {volume});
    gmsh::write((dir / "hex.msh").string());
  }
  expect_parts(layout_error(with_file(small_layered_soil(), dir / "hex.msh"), footprints),
               {"hex.msh' holds no linear tetrahedra (gmsh element type 4): it has 1 "
                "\"Hexahedron 8\" (gmsh type 5)",
                "mesh every volume with linear tetrahedra"});
  // Text that is not a mesh is not handed to gmsh (which would run it as a .geo script).
  std::ofstream(dir / "notes.msh") << "Point(1) = {0, 0, 0};\n";
  expect_parts(layout_error(with_file(small_layered_soil(), dir / "notes.msh"), footprints),
               {"notes.msh' is not a gmsh mesh file: it does not start with $MeshFormat"});
}

/// One tetrahedron as MSH 2.2: node 4 at (x4, 0, -1), the ground face at z = 0, the absorbing
/// ones below; with `stray`, a fifth node and a ground face using it that no tetrahedron has.
std::string one_tetrahedron(const std::string& x4, bool stray = false) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"ground\"\n"
         "2 2 \"absorbing\"\n$EndPhysicalNames\n$Nodes\n" +
         std::string(stray ? "5" : "4") + "\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 " + x4 + " 0 -1\n" +
         (stray ? "5 2 2 0\n" : "") + "$EndNodes\n$Elements\n" + (stray ? "6" : "5") +
         "\n1 4 2 3 1 1 2 3 4\n2 2 2 1 1 1 2 3\n3 2 2 2 2 1 2 4\n4 2 2 2 2 1 3 4\n"
         "5 2 2 2 2 2 3 4\n" +
         (stray ? "6 2 2 1 1 2 3 5\n" : "") + "$EndElements\n";
}

// Found by the msh fuzz targets (tests/fuzz/, docs/fuzzing.md): gmsh reads "nan" and "inf" as
// coordinates, which reached the node order (undefined conversions) and every operator; a face
// with a node of no tetrahedron was refused without naming the file; gmsh threw a standard
// exception on damaged partition tags; nodes at +-1e308 made the node order's extent infinite (a
// NaN key, undefined: the asan preset's UBSan sees it).
TEST(FemMshImport, WhatTheMshFuzzTargetsFoundIsRefusedNamingTheFileOrRead) {
  const fs::path dir = scratch();
  const fem::FemSettings s = rumble::test::soil_settings(750e6, 0.3, 1800.0);
  const std::string where = "fem: params/mesh/file: '" + (dir / "t.msh").string() + "'";
  std::ofstream(dir / "t.msh") << one_tetrahedron("0");
  EXPECT_EQ(fem::load_mesh_file(s, (dir / "t.msh").string()).mesh.tets.size(), 1u);
  std::ofstream(dir / "t.msh") << one_tetrahedron("nan");
  expect_invalid_argument([&] { fem::load_mesh_file(s, (dir / "t.msh").string()); },
                          where +
                              ": a node of its tetrahedra is at x = nan, y = 0, z = -1 m; every "
                              "coordinate must be a finite number");
  std::ofstream(dir / "t.msh") << one_tetrahedron("0", true);
  expect_invalid_argument([&] { fem::load_mesh_file(s, (dir / "t.msh").string()); },
                          where +
                              ": a face of its physical surface \"ground\" has a node that no "
                              "tetrahedron has; the physical surfaces must be made of faces of "
                              "the mesh's tetrahedra");
  // Element tags of a damaged partition made gmsh throw std::length_error, not its own error
  // type: it escaped as "vector::_M_fill_insert" (tests/fuzz/regressions/msh_raw/).
  const fs::path damaged = fs::path(RUMBLE_TEST_SOURCE_DIR) / "tests" / "fuzz" / "regressions" /
                           "msh_raw" / "damaged_partition_tags";
  expect_invalid_argument_containing(
      [&] { fem::load_mesh_file(s, damaged.string()); },
      {"fem: params/mesh/file: '" + damaged.string() + "': gmsh cannot read it: "});
  std::ofstream(dir / "t.msh") << one_tetrahedron("1e308");
  EXPECT_EQ(fem::load_mesh_file(s, (dir / "t.msh").string()).mesh.node_count(), 4);
  std::ofstream(dir / "t.msh") << one_tetrahedron("-1.7e308");
  EXPECT_EQ(fem::load_mesh_file(s, (dir / "t.msh").string()).mesh.node_count(), 4);
}

// gmsh::initialize appends the executable's folder to PATH and PYTHONPATH at every session; glibc
// keeps each replaced value, so the msh fuzz target's thousands of sessions ran out of memory
// (quadratically: each value a little longer). A session leaves both as they were.
TEST(FemMshImport, AGmshSessionLeavesTheEnvironmentAsItWas) {
  const char* path = std::getenv("PATH");
  ASSERT_NE(path, nullptr);
  const std::string before = path;
  ::unsetenv("PYTHONPATH");
  for (int i = 0; i < 3; ++i) {
    const fem::GmshSession session(1);
  }
  EXPECT_EQ(std::getenv("PATH"), before);
  EXPECT_EQ(std::getenv("PYTHONPATH"), nullptr);
}

TEST(FemMshImport, TheFileItselfIsCheckedWhenTheSoilIsMade) {
  const fs::path dir = scratch();
  const nlohmann::json soil = small_layered_soil();
  EXPECT_EQ(creation_error("fem", with_file(soil, dir / "none.msh").dump()),
            "fem: params/mesh/file: no such file \"" + (dir / "none.msh").string() + "\", got \"" +
                (dir / "none.msh").string() +
                "\"; give the path of a mesh file relative to the scenario file's directory "
                "(\".\")");
  EXPECT_EQ(creation_error("fem", with_file(soil, dir).dump()),
            "fem: params/mesh/file: \"" + dir.string() +
                "\" is not a regular file (a directory, device or pipe), got \"" + dir.string() +
                "\"; name a gmsh mesh file (.msh)");
  std::ofstream(dir / "big.msh") << "$MeshFormat\n";
  fs::resize_file(dir / "big.msh", 65u << 20);  // sparse: costs no disk
  nlohmann::json big = with_file(soil, dir / "big.msh");
  big["mesh"]["max_dofs"] = 1e5;
  EXPECT_EQ(creation_error("fem", big.dump()),
            "fem: params/mesh/file: \"" + (dir / "big.msh").string() +
                "\" is too large (68157440 bytes; a mesh file is at most 67108864 bytes), got \"" +
                (dir / "big.msh").string() +
                "\"; is this the right file? (the limit is 256 bytes per mesh.max_dofs, now "
                "1e+05; raise it for a larger mesh)");
  nlohmann::json same_name = soil;
  same_name["layers"].push_back(soil["layers"][0]);
  EXPECT_EQ(creation_error("fem", same_name.dump()),
            "fem: params/layers/1/name: \"fill\" names params/layers/0 already; give each layer "
            "its own name");
}

}  // namespace
}  // namespace rumble::test
