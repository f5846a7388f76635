// A user's mesh file (mesh.file) taken in: every check that turns a file gmsh can open into a
// mesh the soil can step, each refusal naming the file, what it has and the fix. Kept apart from
// the model's reading because these checks are what the msh fuzz target exercises and grows.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_reading.hpp"
#include "mesh/mesh_memory.hpp"
#include "mesh/node_order.hpp"

namespace rumble::fem {

std::string where_file(const std::string& path) {
  return "fem: params/mesh/file: '" + path + "'";
}

namespace {

/// The connected patches (faces sharing a node) of faces, as rectangles.
std::vector<MeshFootprint> patches(const TetMesh& mesh, const std::vector<Triangle>& faces) {
  std::vector<std::int32_t> parent(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) parent[i] = static_cast<std::int32_t>(i);
  const auto root = [&](std::int32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::unordered_map<std::int32_t, std::int32_t> face_of_node;
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::int32_t v : faces[i]) {
      const auto [it, inserted] = face_of_node.emplace(v, static_cast<std::int32_t>(i));
      if (!inserted) parent[root(static_cast<std::int32_t>(i))] = root(it->second);
    }
  std::map<std::int32_t, MeshFootprint> by_root;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto [it, inserted] = by_root.try_emplace(root(static_cast<std::int32_t>(i)));
    MeshFootprint& p = it->second;
    if (inserted) {
      p.x0 = p.y0 = std::numeric_limits<double>::max();
      p.x1 = p.y1 = std::numeric_limits<double>::lowest();
    }
    for (std::int32_t v : faces[i]) {
      p.x0 = std::min(p.x0, mesh.nodes(0, v));
      p.x1 = std::max(p.x1, mesh.nodes(0, v));
      p.y0 = std::min(p.y0, mesh.nodes(1, v));
      p.y1 = std::max(p.y1, mesh.nodes(1, v));
    }
    p.area += triangle_area(mesh, faces[i], nullptr);
  }
  std::vector<MeshFootprint> out;
  for (const auto& [r, p] : by_root) out.push_back(p);
  std::sort(out.begin(), out.end(), [](const MeshFootprint& a, const MeshFootprint& b) {
    return a.centre_x() != b.centre_x() ? a.centre_x() < b.centre_x() : a.centre_y() < b.centre_y();
  });
  return out;
}

/// Element types of dimension 3 in the current model, named: "4 Tetrahedron 4, ..." .
std::string volume_element_types(const std::vector<int>& types) {
  std::string out;
  for (int type : types) {
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
    std::vector<std::size_t> tags, node_tags;
    gmsh::model::mesh::getElementsByType(type, tags, node_tags);
    out += (out.empty() ? "" : ", ") + std::to_string(tags.size()) + " \"" + name +
           "\" (gmsh type " + std::to_string(type) + ")";
  }
  return out.empty() ? "no volume elements" : out;
}

// Only gmsh's mesh format: gmsh::open would take anything else for a .geo script and run it.
void check_is_msh(const std::string& path, const std::string& where) {
  if (!std::filesystem::is_regular_file(path))
    throw std::invalid_argument(where +
                                " is not a file; give the path of a gmsh .msh, relative "
                                "to the scenario's folder");
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first != "$MeshFormat")
    throw std::invalid_argument(
        where +
        " is not a gmsh mesh file: it does not start with $MeshFormat; give a .msh written by "
        "gmsh (File > Export, or gmsh -3 model.geo -o soil.msh; formats 2.2 and 4.1)");
}

void open_msh(const std::string& path, const std::string& where) {
  try {
    gmsh::open(path);
  } catch (const std::string& message) {
    throw std::invalid_argument(where + ": gmsh cannot read it: " + message);
  } catch (const std::exception& e) {  // from gmsh's containers: std::length_error on a damaged
                                       // partition tag (found by the msh fuzz target)
    throw std::invalid_argument(where + ": gmsh cannot read it: " + e.what());
  }
}

// The open model's volumes hold linear tetrahedra and nothing else.
void check_linear_tetrahedra(const std::string& where) {
  std::vector<int> types;
  gmsh_call("read the element types", [&] {
    gmsh::model::mesh::getElementTypes(types, 3);
    return 0;
  });
  const bool linear_tets = std::find(types.begin(), types.end(), 4) != types.end();
  if (linear_tets && types.size() == 1) return;
  const std::string found =
      gmsh_call("name the element types", [&] { return volume_element_types(types); });
  throw std::invalid_argument(
      where +
      (linear_tets ? " holds other volume elements besides linear tetrahedra"
                   : " holds no linear tetrahedra (gmsh element type 4)") +
      ": it has " + found +
      "; mesh every volume with linear tetrahedra (gmsh: Mesh.ElementOrder = 1, no "
      "recombination into hexahedra or prisms)");
}

// The open model's physical surfaces into file.surfaces: "ground" and "absorbing" needed,
// "footprints" noted.
void read_surface_groups(const std::string& where, MeshFile& file) {
  const auto surfaces = gmsh_call("read the physical groups", [] { return physical_groups(2); });
  for (const auto& [name, tag] : surfaces) file.surfaces.push_back(name);
  std::string missing;
  for (const char* name : {"ground", "absorbing"})
    if (surfaces.count(name) == 0)
      missing += std::string(missing.empty() ? "" : " and ") + '"' + name + '"';
  if (!missing.empty())
    throw std::invalid_argument(where + " has no physical surface " + missing +
                                " (it has: " + quoted_list(file.surfaces) +
                                "); name the free surface at z = 0 \"ground\" (the footprints lie "
                                "in it) and the truncation surface \"absorbing\"");
  file.has_footprints = surfaces.count("footprints") > 0;
}

// gmsh reads "nan" and "inf" as coordinates; no operator (nor the node order) takes them (found
// by the msh fuzz target).
void check_finite_nodes(const TetMesh& mesh, const std::string& where) {
  for (Eigen::Index i = 0; i < mesh.nodes.cols(); ++i)
    if (!mesh.nodes.col(i).allFinite()) {
      std::ostringstream m;
      m << where << ": a node of its tetrahedra is at x = " << mesh.nodes(0, i)
        << ", y = " << mesh.nodes(1, i) << ", z = " << -mesh.nodes(2, i)
        << " m; every coordinate must be a finite number";
      throw std::invalid_argument(m.str());
    }
}

void check_ground_plane(const TetMesh& mesh, const std::string& where) {
  for (const Triangle& f : mesh.ground)
    for (std::int32_t v : f)
      if (std::abs(mesh.nodes(2, v)) > 1e-6) {
        std::ostringstream m;
        m << where << ": a node of the physical surface \"ground\" is at z = " << -mesh.nodes(2, v)
          << " m; the ground must be the plane z = 0 (z up, soil below)";
        throw std::invalid_argument(m.str());
      }
}

// Within mesh.max_dofs and the memory available now.
void check_mesh_size(const FemSettings& s, const TetMesh& mesh, const std::string& where) {
  if (static_cast<double>(mesh.dof_count()) > s.mesh.max_dofs) {
    std::ostringstream m;
    m << where << " has " << mesh.dof_count()
      << " degrees of freedom, more than mesh.max_dofs = " << s.mesh.max_dofs
      << "; give a coarser mesh or raise mesh.max_dofs (about "
      << peak_bytes_per_million_dofs() * 1e-9 << " GB per million DOFs at a run's peak)";
    throw std::invalid_argument(m.str());
  }
  check_memory_for(static_cast<double>(mesh.dof_count()), where, "give a coarser mesh");
}

}  // namespace

MeshFile load_mesh_file(const FemSettings& s, const std::string& path) {
  const std::string where = where_file(path);
  check_is_msh(path, where);
  GmshSession session(1);
  open_msh(path, where);
  MeshFile file;
  file.path = path;
  check_linear_tetrahedra(where);
  read_surface_groups(where, file);
  std::vector<Triangle> footprint_faces;
  file.mesh = read_grouped(s, where, &footprint_faces);
  check_finite_nodes(file.mesh, where);
  order_nodes_spatially(file.mesh, &footprint_faces);  // as generated meshes: node_order.hpp
  check_ground_plane(file.mesh, where);
  check_mesh_size(s, file.mesh, where);
  file.footprints = patches(file.mesh, footprint_faces);
  return file;
}

TetMesh read_mesh_file(const FemSettings& s, const std::string& path) {
  return load_mesh_file(s, path).mesh;
}

}  // namespace rumble::fem
