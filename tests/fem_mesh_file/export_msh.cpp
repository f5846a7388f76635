// fem_export_msh SCENARIO OUT.msh: the FEM soil's own mesh of a scenario (its soil.params without
// mesh.file, on its track's footprints) written as a gmsh .msh with the physical groups that
// mesh.file reads (docs/fem-soil.md §2): a starting point for a user's mesh, and the mesh of the
// example scenarios/examples/fem_user_mesh.json, made when its test runs (tests/scenarios).
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/mesh_generator.hpp"
#include "scenario/scenario_schema.hpp"
#include "settings_from_params.hpp"
#include "track_spec/footprint_layout.hpp"
#include "track_spec/track_config.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: fem_export_msh SCENARIO OUT.msh\n";
    return 2;
  }
  try {
    std::ifstream in(argv[1]);
    if (!in) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    const nlohmann::json scenario = nlohmann::json::parse(in);
    nlohmann::json params = scenario.at("soil").at("params");
    if (params.contains("mesh")) params["mesh"].erase("file");
    const std::vector<rumble_footprint> footprints =
        rumble::footprint_layout(rumble::TrackConfig::from_json(
            rumble::scenario::track_with_defaults(scenario.at("track"))));
    const rumble::fem::FemSettings s = rumble::test::settings_from(params);
    const rumble::fem::TetMesh mesh =
        rumble::fem::generate_mesh(s, footprints, rumble::fem::plan_mesh(s, footprints));
    const std::filesystem::path out(argv[2]);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    rumble::fem::write_mesh_file(mesh, s, footprints, out.string());
    std::cout << "wrote " << argv[2] << ": " << mesh.node_count() << " nodes, " << mesh.tets.size()
              << " tetrahedra, " << footprints.size() << " footprints\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "fem_export_msh: " << e.what() << "\n";
    return 1;
  }
}
