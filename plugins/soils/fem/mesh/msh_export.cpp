// mesh.export: a TetMesh written as a .msh that mesh.file reads back as the same mesh. The only
// gmsh code that builds a model from the soil's arrays, so it sits apart from the readers.
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mesh/gmsh_model.hpp"

namespace rumble::fem {

void write_mesh_file(const TetMesh& mesh, const FemSettings& s,
                     const std::vector<Footprint>& footprints, const std::string& path) {
  GmshSession session(1);
  gmsh_call("write the mesh", [&] {
    namespace gm = gmsh::model;
    const auto n = static_cast<std::size_t>(mesh.node_count());
    std::vector<std::size_t> node_tags(n);
    std::vector<double> xyz(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      node_tags[i] = i + 1;
      const auto c = static_cast<Eigen::Index>(i);
      xyz[3 * i] = mesh.nodes(0, c);
      xyz[3 * i + 1] = mesh.nodes(1, c);
      xyz[3 * i + 2] = -mesh.nodes(2, c);  // z up in gmsh
    }
    std::size_t element_tag = 1;
    // One volume per run of tetrahedra of one layer: their order is kept.
    std::map<std::uint16_t, std::vector<int>> volumes_of_layer;
    for (std::size_t e = 0; e < mesh.tets.size();) {
      std::size_t end = e;
      while (end < mesh.tets.size() && mesh.layer[end] == mesh.layer[e]) ++end;
      const int volume = gm::addDiscreteEntity(3);
      if (volumes_of_layer.empty()) gm::mesh::addNodes(3, volume, node_tags, xyz);
      std::vector<std::size_t> tags, nodes;
      for (std::size_t k = e; k < end; ++k) {
        const Tetrahedron& t = mesh.tets[k];
        tags.push_back(element_tag++);
        // Mirrored by depth -> z: swap two nodes to keep the volume positive.
        for (std::int32_t v : {t[0], t[1], t[3], t[2]})
          nodes.push_back(static_cast<std::size_t>(v) + 1);
      }
      gm::mesh::addElementsByType(volume, 4, tags, nodes);
      volumes_of_layer[mesh.layer[e]].push_back(volume);
      e = end;
    }
    const auto add_faces = [&](const std::vector<Triangle>& faces, std::size_t begin,
                               std::size_t end) {
      const int surface = gm::addDiscreteEntity(2);
      std::vector<std::size_t> tags, nodes;
      for (std::size_t k = begin; k < end; ++k) {
        tags.push_back(element_tag++);
        for (std::int32_t v : faces[k]) nodes.push_back(static_cast<std::size_t>(v) + 1);
      }
      gm::mesh::addElementsByType(surface, 2, tags, nodes);
      return surface;
    };
    // The ground in runs of faces inside a footprint or not (as footprint_weights tells them).
    const auto in_footprint = [&](const Triangle& f) {
      const double x = (mesh.nodes(0, f[0]) + mesh.nodes(0, f[1]) + mesh.nodes(0, f[2])) / 3.0;
      const double y = (mesh.nodes(1, f[0]) + mesh.nodes(1, f[1]) + mesh.nodes(1, f[2])) / 3.0;
      for (const Footprint& p : footprints)
        if (std::abs(x - p.x) <= 0.5 * p.width && std::abs(y - p.y) <= 0.5 * p.length) return true;
      return false;
    };
    std::vector<int> ground, under_footprints;
    for (std::size_t e = 0; e < mesh.ground.size();) {
      const bool inside = in_footprint(mesh.ground[e]);
      std::size_t end = e;
      while (end < mesh.ground.size() && in_footprint(mesh.ground[end]) == inside) ++end;
      (inside ? under_footprints : ground).push_back(add_faces(mesh.ground, e, end));
      e = end;
    }
    const int truncation = add_faces(mesh.truncation, 0, mesh.truncation.size());
    gm::setPhysicalName(2, gm::addPhysicalGroup(2, ground), "ground");
    if (!under_footprints.empty())
      gm::setPhysicalName(2, gm::addPhysicalGroup(2, under_footprints), "footprints");
    gm::setPhysicalName(2, gm::addPhysicalGroup(2, {truncation}), "absorbing");
    for (const auto& [layer, volumes] : volumes_of_layer)
      gm::setPhysicalName(3, gm::addPhysicalGroup(3, volumes), mesh_layer_names(s, layer).front());
    gmsh::option::setNumber("Mesh.Binary", 1);  // exact coordinates, a third of the size
    gmsh::write(path);
    return 0;
  });
}

}  // namespace rumble::fem
