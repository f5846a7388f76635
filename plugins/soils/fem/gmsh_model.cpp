#include "gmsh_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace rumble::fem {

namespace {

/// Physical groups of dimension dim by name.
std::map<std::string, int> physical_groups(int dim) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  std::map<std::string, int> named;
  for (const auto& [d, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    named[name] = tag;
  }
  return named;
}

std::vector<int> entities_of(int dim, int group) {
  std::vector<int> tags;
  gmsh::model::getEntitiesForPhysicalGroup(dim, group, tags);
  return tags;
}

}  // namespace

TetMesh read_model(const FemSettings& s, bool by_physical_groups) {
  TetMesh mesh;
  gmsh_call("read the mesh", [&] {
    std::vector<std::size_t> node_tags, tet_tags, tet_nodes;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(node_tags, xyz, parametric, -1, -1, false, false);
    gmsh::model::mesh::getElementsByType(4, tet_tags, tet_nodes);
    // Keep the nodes the tetrahedra use, numbered in gmsh's order.
    std::unordered_map<std::size_t, std::size_t> position;
    position.reserve(node_tags.size());
    for (std::size_t i = 0; i < node_tags.size(); ++i) position.emplace(node_tags[i], i);
    std::vector<std::int32_t> index(node_tags.size(), -1);
    std::int32_t used = 0;
    for (std::size_t tag : tet_nodes) {
      std::int32_t& k = index[position.at(tag)];
      if (k < 0) k = used++;
    }
    mesh.nodes.resize(3, used);
    for (std::size_t i = 0; i < node_tags.size(); ++i)
      if (index[i] >= 0) mesh.nodes.col(index[i]) << xyz[3 * i], xyz[3 * i + 1], -xyz[3 * i + 2];
    const auto node = [&](std::size_t tag) {
      const std::int32_t k = index[position.at(tag)];
      if (k < 0) throw std::invalid_argument("a boundary face uses a node of no tetrahedron");
      return k;
    };
    mesh.tets.resize(tet_tags.size());
    mesh.layer.resize(tet_tags.size());
    std::unordered_map<std::size_t, std::size_t> tet_position;
    for (std::size_t e = 0; e < tet_tags.size(); ++e) {
      tet_position.emplace(tet_tags[e], e);
      Tetrahedron t{node(tet_nodes[4 * e]), node(tet_nodes[4 * e + 1]), node(tet_nodes[4 * e + 2]),
                    node(tet_nodes[4 * e + 3])};
      if (tet_volume(mesh, t) < 0.0) std::swap(t[2], t[3]);  // mirrored by z -> depth
      mesh.tets[e] = t;
      const double depth = 0.25 * (mesh.nodes(2, t[0]) + mesh.nodes(2, t[1]) + mesh.nodes(2, t[2]) +
                                   mesh.nodes(2, t[3]));
      double bottom = 0.0;
      std::uint16_t layer = 0;
      for (const soils::SoilLayer& l : s.layers) {
        bottom += l.thickness;
        if (depth < bottom) break;
        ++layer;
      }
      mesh.layer[e] = layer;
    }
    const auto faces_of = [&](int surface, std::vector<Triangle>& out) {
      std::vector<std::size_t> tri_tags, tri_nodes;
      gmsh::model::mesh::getElementsByType(2, tri_tags, tri_nodes, surface);
      for (std::size_t e = 0; e < tri_tags.size(); ++e)
        out.push_back(
            {node(tri_nodes[3 * e]), node(tri_nodes[3 * e + 1]), node(tri_nodes[3 * e + 2])});
    };
    if (by_physical_groups) {
      const auto surfaces = physical_groups(2);
      for (int e : entities_of(2, surfaces.at("ground"))) faces_of(e, mesh.ground);
      for (int e : entities_of(2, surfaces.at("absorbing"))) faces_of(e, mesh.truncation);
      for (const auto& [name, group] : physical_groups(3)) {
        if (name.rfind("layer_", 0) != 0) continue;
        const auto layer = static_cast<std::uint16_t>(std::stoi(name.substr(6)));
        for (int volume : entities_of(3, group)) {
          std::vector<std::size_t> tags, nodes;
          gmsh::model::mesh::getElementsByType(4, tags, nodes, volume);
          for (std::size_t tag : tags) mesh.layer[tet_position.at(tag)] = layer;
        }
      }
      return 0;
    }
    // Faces of the surfaces that bound one volume only: the ground, or the truncation.
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    const double extent =
        (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).maxCoeff();
    const double ground_tolerance = 1e-9 * extent;
    for (const auto& [dim, tag] : surfaces) {
      std::vector<int> up, down;
      gmsh::model::getAdjacencies(dim, tag, up, down);
      if (up.size() != 1) continue;
      std::vector<Triangle> faces;
      faces_of(tag, faces);
      for (const Triangle& f : faces) {
        const bool on_ground = std::abs(mesh.nodes(2, f[0])) < ground_tolerance &&
                               std::abs(mesh.nodes(2, f[1])) < ground_tolerance &&
                               std::abs(mesh.nodes(2, f[2])) < ground_tolerance;
        (on_ground ? mesh.ground : mesh.truncation).push_back(f);
      }
    }
    return 0;
  });
  return mesh;
}

TetMesh read_mesh_file(const FemSettings& s, const std::string& path) {
  const std::string where = "fem: params/mesh/file: '" + path + "'";
  if (!std::filesystem::is_regular_file(path))
    throw std::invalid_argument(where +
                                " is not a file; give the path of a gmsh .msh, relative "
                                "to the scenario's folder");
  GmshSession session(1);
  try {
    gmsh::open(path);
  } catch (const std::string& message) {
    throw std::invalid_argument(where + ": gmsh cannot read it: " + message);
  }
  const auto surfaces = gmsh_call("read the physical groups", [] { return physical_groups(2); });
  std::string missing;
  for (const char* name : {"ground", "absorbing"})
    if (surfaces.count(name) == 0)
      missing += std::string(missing.empty() ? "" : " and ") + '"' + name + '"';
  if (!missing.empty()) {
    std::string have;
    for (const auto& [name, tag] : surfaces)
      have += (have.empty() ? "" : ", ") + ('"' + name + '"');
    throw std::invalid_argument(where + " has no physical surface " + missing +
                                " (it has: " + (have.empty() ? "none" : have) +
                                "); name the free surface at z = 0 \"ground\" (the footprints lie "
                                "in it) and the truncation surface \"absorbing\"");
  }
  TetMesh mesh = read_model(s, /*by_physical_groups=*/true);
  if (mesh.tets.empty())
    throw std::invalid_argument(where + " holds no linear tetrahedra (gmsh element type 4)");
  for (const Triangle& f : mesh.ground)
    for (std::int32_t v : f)
      if (std::abs(mesh.nodes(2, v)) > 1e-6) {
        std::ostringstream m;
        m << where << ": a node of the physical surface \"ground\" is at z = " << -mesh.nodes(2, v)
          << " m; the ground must be the plane z = 0 (z up, soil below)";
        throw std::invalid_argument(m.str());
      }
  return mesh;
}

}  // namespace rumble::fem
