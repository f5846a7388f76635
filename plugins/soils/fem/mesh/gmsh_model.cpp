// The current gmsh model read back into a TetMesh, by geometry (a generated mesh) or by physical
// groups (a user's): gmsh's node and element tags become the mesh's rows here and nowhere else,
// so the other gmsh files work on TetMesh alone.
#include "mesh/gmsh_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/gmsh_reading.hpp"

namespace rumble::fem {

namespace {

/// A physical group without a name is listed as this, with its tag.
constexpr const char* kUnnamed = "(unnamed, tag ";

bool unnamed(const std::string& name) {
  return name.rfind(kUnnamed, 0) == 0;
}

std::vector<int> entities_of(int dim, int group) {
  std::vector<int> tags;
  gmsh::model::getEntitiesForPhysicalGroup(dim, group, tags);
  return tags;
}

/// The layer a physical volume's name stands for, or -1.
int layer_of_volume(const FemSettings& s, const std::string& name) {
  for (std::size_t k = 0; k <= s.layers.size(); ++k)
    for (const std::string& n : mesh_layer_names(s, k))
      if (n == name) return static_cast<int>(k);
  return -1;
}

/// Node tags' rows and the rows of tets, shared by the readers below.
struct ModelIndex {
  std::unordered_map<std::size_t, std::size_t> position;  // node tag -> position in getNodes
  std::vector<std::int32_t> index;                        // position -> mesh node, -1 unused
  std::unordered_map<std::size_t, std::size_t> tet_position;
  std::int32_t node(std::size_t tag) const {
    const auto p = position.find(tag);
    const std::int32_t k = p == position.end() ? -1 : index[p->second];
    if (k < 0) throw std::invalid_argument("a boundary face uses a node of no tetrahedron");
    return k;
  }
};

void faces_of(const ModelIndex& ix, int surface, std::vector<Triangle>& out) {
  std::vector<std::size_t> tri_tags, tri_nodes;
  gmsh::model::mesh::getElementsByType(2, tri_tags, tri_nodes, surface);
  for (std::size_t e = 0; e < tri_tags.size(); ++e)
    out.push_back(
        {ix.node(tri_nodes[3 * e]), ix.node(tri_nodes[3 * e + 1]), ix.node(tri_nodes[3 * e + 2])});
}

/// The current model's nodes and tetrahedra, layers by depth.
TetMesh read_tets(const FemSettings& s, ModelIndex& ix) {
  TetMesh mesh;
  std::vector<std::size_t> node_tags, tet_tags, tet_nodes;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(node_tags, xyz, parametric, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(4, tet_tags, tet_nodes);
  // Keep the nodes the tetrahedra use, numbered in the order they first appear in them.
  ix.position.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) ix.position.emplace(node_tags[i], i);
  ix.index.assign(node_tags.size(), -1);
  std::int32_t used = 0;
  for (std::size_t tag : tet_nodes) {
    std::int32_t& k = ix.index[ix.position.at(tag)];
    if (k < 0) k = used++;
  }
  mesh.nodes.resize(3, used);
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    if (ix.index[i] >= 0)
      mesh.nodes.col(ix.index[i]) << xyz[3 * i], xyz[3 * i + 1], -xyz[3 * i + 2];
  mesh.tets.resize(tet_tags.size());
  mesh.layer.resize(tet_tags.size());
  for (std::size_t e = 0; e < tet_tags.size(); ++e) {
    ix.tet_position.emplace(tet_tags[e], e);
    Tetrahedron t{ix.node(tet_nodes[4 * e]), ix.node(tet_nodes[4 * e + 1]),
                  ix.node(tet_nodes[4 * e + 2]), ix.node(tet_nodes[4 * e + 3])};
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
  return mesh;
}

std::string format_number(double x) {
  std::ostringstream m;
  m.precision(6);
  m << x;
  return m.str();
}

}  // namespace

std::map<std::string, int> physical_groups(int dim) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  std::map<std::string, int> named;
  for (const auto& [d, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    named[name.empty() ? kUnnamed + std::to_string(tag) + ")" : name] = tag;
  }
  return named;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names)
    out += (out.empty() ? "" : ", ") + (unnamed(n) ? n : '"' + n + '"');
  return out.empty() ? "none" : out;
}

std::vector<std::string> mesh_layer_names(const FemSettings& s, std::size_t k) {
  std::vector<std::string> names;
  if (k < s.layers.size()) {
    if (k < s.layer_names.size() && !s.layer_names[k].empty()) names.push_back(s.layer_names[k]);
  } else {
    names.emplace_back("half_space");
  }
  names.push_back("layer_" + std::to_string(k));
  return names;
}

namespace {

/// Layers from the physical volumes named for them (mesh_layer_names); unnamed volumes are
/// ignored, and without named ones the layers stay by depth.
void layers_from_volumes(const FemSettings& s, const ModelIndex& ix, const std::string& where,
                         TetMesh& mesh) {
  std::vector<std::string> unknown;
  std::vector<char> assigned(mesh.tets.size(), 0), present(s.layers.size() + 1, 0);
  bool named = false;
  for (const auto& [name, group] : physical_groups(3)) {
    if (unnamed(name)) continue;
    const int layer = layer_of_volume(s, name);
    if (layer < 0) {
      unknown.push_back(name);
      continue;
    }
    named = true;
    present[static_cast<std::size_t>(layer)] = 1;
    for (int volume : entities_of(3, group)) {
      std::vector<std::size_t> tags, nodes;
      gmsh::model::mesh::getElementsByType(4, tags, nodes, volume);
      for (std::size_t tag : tags) {
        const std::size_t e = ix.tet_position.at(tag);
        mesh.layer[e] = static_cast<std::uint16_t>(layer);
        assigned[e] = 1;
      }
    }
  }
  std::vector<std::string> accepted;
  for (std::size_t k = 0; k <= s.layers.size(); ++k)
    for (const std::string& n : mesh_layer_names(s, k)) accepted.push_back(n);
  if (!unknown.empty())
    throw std::invalid_argument(
        where + " has the physical volume(s) " + quoted_list(unknown) +
        ", which name no layer of params/layers; name each volume for its layer: " +
        quoted_list(accepted) +
        " (a layer's \"name\", layer_<k> with k = 0 the top layer, half_space below the "
        "layers), or leave the volumes unnamed to take the layers by depth");
  if (!named) return;
  const auto unassigned = std::count(assigned.begin(), assigned.end(), 0);
  if (unassigned > 0)
    throw std::invalid_argument(
        where + ": " + std::to_string(unassigned) + " of " + std::to_string(mesh.tets.size()) +
        " tetrahedra are in no physical volume named for a layer; put every volume in one (" +
        quoted_list(accepted) + ")");
  // Every layer the mesh reaches down to must have its volume.
  const double deepest = mesh.nodes.row(2).maxCoeff();
  double top = 0.0;
  for (std::size_t k = 0; k <= s.layers.size(); ++k) {
    if (top >= deepest) break;
    if (!present[k])
      throw std::invalid_argument(where + " has no physical volume for " +
                                  (k < s.layers.size() ? "params/layers/" + std::to_string(k)
                                                       : std::string("the half-space")) +
                                  " (from " + format_number(top) + " m deep; the mesh reaches " +
                                  format_number(deepest) + " m); name its volume " +
                                  quoted_list(mesh_layer_names(s, k)));
    if (k < s.layers.size()) top += s.layers[k].thickness;
  }
}

}  // namespace

TetMesh read_grouped(const FemSettings& s, const std::string& where,
                     std::vector<Triangle>* footprint_faces) {
  TetMesh mesh;
  gmsh_call("read the mesh", [&] {
    ModelIndex ix;
    mesh = read_tets(s, ix);
    const auto surfaces = physical_groups(2);
    // The ground: its own faces and the footprints', each surface once, in gmsh's order.
    std::set<int> ground;
    for (const char* name : {"ground", "footprints"})
      if (const auto g = surfaces.find(name); g != surfaces.end())
        for (int e : entities_of(2, g->second)) ground.insert(e);
    // A face with a node no tetrahedron has (ModelIndex::node) named neither the file nor the
    // surface (found by the msh fuzz target).
    const auto faces = [&](const char* group, int entity, std::vector<Triangle>& out) {
      try {
        faces_of(ix, entity, out);
      } catch (const std::invalid_argument&) {
        throw std::invalid_argument(where + ": a face of its physical surface \"" + group +
                                    "\" has a node that no tetrahedron has; the physical "
                                    "surfaces must be made of faces of the mesh's tetrahedra");
      }
    };
    const std::vector<int> own = entities_of(2, surfaces.at("ground"));
    for (int e : ground)
      faces(std::find(own.begin(), own.end(), e) != own.end() ? "ground" : "footprints", e,
            mesh.ground);
    for (int e : entities_of(2, surfaces.at("absorbing"))) faces("absorbing", e, mesh.truncation);
    if (const auto f = surfaces.find("footprints"); f != surfaces.end() && footprint_faces)
      for (int e : entities_of(2, f->second)) faces("footprints", e, *footprint_faces);
    layers_from_volumes(s, ix, where, mesh);
    return 0;
  });
  return mesh;
}

TetMesh read_model(const FemSettings& s) {
  TetMesh mesh;
  gmsh_call("read the mesh", [&] {
    ModelIndex ix;
    mesh = read_tets(s, ix);
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
      faces_of(ix, tag, faces);
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

}  // namespace rumble::fem
