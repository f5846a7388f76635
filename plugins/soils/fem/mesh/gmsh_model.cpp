#include "mesh/gmsh_model.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "mesh/mesh_memory.hpp"
#include "mesh/node_order.hpp"

namespace rumble::fem {

namespace {

/// A physical group without a name is listed as this, with its tag.
constexpr const char* kUnnamed = "(unnamed, tag ";

/// Physical groups of dimension dim by name (unnamed ones as kUnnamed<tag>)).
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

bool unnamed(const std::string& name) {
  return name.rfind(kUnnamed, 0) == 0;
}

std::vector<int> entities_of(int dim, int group) {
  std::vector<int> tags;
  gmsh::model::getEntitiesForPhysicalGroup(dim, group, tags);
  return tags;
}

/// "\"a\", \"b\"" or "none".
std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names)
    out += (out.empty() ? "" : ", ") + (unnamed(n) ? n : '"' + n + '"');
  return out.empty() ? "none" : out;
}

std::string where_file(const std::string& path) {
  return "fem: params/mesh/file: '" + path + "'";
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

std::string format_number(double x) {
  std::ostringstream m;
  m.precision(6);
  m << x;
  return m.str();
}

/// x to 1 nm, for messages (a centre at -1e-17 m reads 0).
double nm(double x) {
  const double r = std::round(x * 1e9) / 1e9;
  return r == 0.0 ? 0.0 : r;
}

/// Debian's gmsh links FLTK 1.3 (its GUI), whose first look at one of its options reads and
/// rewrites its preference files, /etc/fltk/fltk.org/fltk.prefs (as root) and
/// ~/.fltk/fltk.org/fltk.prefs (made when missing); gmsh::initialize looks (its default
/// General.Tooltips switches FLTK's tooltips on). Marking FLTK's options as read already keeps it
/// from both; their values matter only to a GUI, which the plugin never opens. Nothing to do
/// where gmsh is built without FLTK.
void keep_fltk_from_its_preference_files() {
  void* fltk = ::dlopen("libfltk.so.1.3", RTLD_LAZY | RTLD_NOLOAD);
  if (fltk == nullptr) return;
  if (auto* read = static_cast<unsigned char*>(::dlsym(fltk, "_ZN2Fl13options_read_E")))
    *read = 1;  // Fl::options_read_
  ::dlclose(fltk);
}

}  // namespace

GmshSession::GmshSession(unsigned threads) {
  keep_fltk_from_its_preference_files();
  // gmsh::initialize appends the executable's folder to PATH and PYTHONPATH (for its ONELAB
  // clients and Python modules, which the plugin never uses) at every session: they grew each
  // time, and glibc keeps every value setenv replaces, so thousands of sessions in one process
  // took memory quadratically (the msh fuzz target ran out of its 2 GiB). Put back as they were,
  // the same values are reused.
  std::vector<std::pair<const char*, std::optional<std::string>>> environment;
  for (const char* name : {"PATH", "PYTHONPATH"}) {
    const char* value = std::getenv(name);
    environment.emplace_back(name,
                             value != nullptr ? std::optional<std::string>(value) : std::nullopt);
  }
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);  // no ~/.gmshrc, ~/.gmsh-options
  for (const auto& [name, value] : environment)
    value ? ::setenv(name, value->c_str(), 1) : ::unsetenv(name);
  // Nothing saved at the end (the GUI's session and options files), and gmsh::finalize removes
  // its temporary file, by default ~/.gmsh-tmp (a user's, from gmsh's GUI): named "." instead,
  // it is the home directory itself, which unlink refuses.
  gmsh::option::setNumber("General.SaveSession", 0);
  gmsh::option::setNumber("General.SaveOptions", 0);
  gmsh::option::setString("General.TmpFileName", ".");
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  gmsh::option::setNumber("General.NumThreads", threads);
  // Same input, same mesh: gmsh otherwise takes as many threads as OpenMP offers per stage.
  for (const char* stage : {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
    gmsh::option::setNumber(stage, threads);
  gmsh::model::add("soil");
}

GmshSession::~GmshSession() {
  gmsh::finalize();
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

/// The current model read by its physical groups (checked present by the caller); the faces
/// of the physical surface "footprints" into footprint_faces when given.
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

}  // namespace

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

namespace {

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
      << "; give a coarser mesh or raise mesh.max_dofs (about " << kPeakBytesPerDof * 1e-3
      << " GB per million DOFs at a run's peak)";
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

double mesh_footprint_tolerance(const Footprint& f) {
  return std::max(1e-3, 0.02 * std::min(f.length, f.width));
}

void check_mesh_footprints(const MeshFile& file, const std::vector<Footprint>& footprints) {
  const std::string where = where_file(file.path);
  // A mesh made for another track: the track's footprints are blamed (the engine reports a
  // layout refusal that names no "fem: params/<key>:" at /track/sleepers), the file named.
  const std::string mismatch =
      "fem: the track's footprints do not fit the mesh of params/mesh/file '" + file.path + "'";
  std::ostringstream track;
  track.precision(6);
  track << "the track has " << footprints.size() << " footprint(s)";
  if (!footprints.empty()) {
    const Footprint& a = footprints.front();
    const Footprint& b = footprints.back();
    track << ", " << a.length << " m x " << a.width
          << " m (across x along), centred at x = " << a.x;
    if (footprints.size() > 1)
      track << " .. " << b.x << " m every "
            << (b.x - a.x) / static_cast<double>(footprints.size() - 1);
    track << " m, y = " << a.y << " m";
  }
  if (!file.has_footprints)
    throw std::invalid_argument(
        where + " has no physical surface \"footprints\" (it has: " + quoted_list(file.surfaces) +
        "); " + track.str() +
        ": embed each footprint's rectangle in the ground and put them in a physical surface "
        "\"footprints\"");
  if (file.footprints.size() != footprints.size()) {
    std::ostringstream m;
    m.precision(6);
    m << mismatch << " has " << file.footprints.size()
      << " footprint rectangle(s) in its physical surface \"footprints\"";
    if (!file.footprints.empty())
      m << " (centred at x = " << nm(file.footprints.front().centre_x()) << " .. "
        << nm(file.footprints.back().centre_x()) << " m)";
    m << "; " << track.str()
      << ": mesh one rectangle per footprint (rectangles must not touch), or change "
         "/track/sleepers to the mesh's";
    throw std::invalid_argument(m.str());
  }
  for (std::size_t j = 0; j < footprints.size(); ++j) {
    const Footprint& f = footprints[j];
    const MeshFootprint* nearest = nullptr;
    double best = std::numeric_limits<double>::max();
    for (const MeshFootprint& p : file.footprints) {
      const double d = std::hypot(p.centre_x() - f.x, p.centre_y() - f.y);
      if (d < best) {
        best = d;
        nearest = &p;
      }
    }
    const double tol = mesh_footprint_tolerance(f);
    const MeshFootprint& p = *nearest;
    if (std::abs(p.centre_x() - f.x) <= tol && std::abs(p.centre_y() - f.y) <= tol &&
        std::abs((p.x1 - p.x0) - f.width) <= tol && std::abs((p.y1 - p.y0) - f.length) <= tol)
      continue;
    std::ostringstream m;
    m.precision(6);
    m << mismatch << ": footprint " << j << " of the track (centre x " << f.x << " m, y " << f.y
      << " m, " << f.length << " m x " << f.width << " m) has no rectangle of the physical "
      << "surface \"footprints\" within " << tol << " m; the nearest is centred at x "
      << nm(p.centre_x()) << " m, y " << nm(p.centre_y()) << " m, " << nm(p.y1 - p.y0) << " m x "
      << nm(p.x1 - p.x0) << " m; " << track.str()
      << ": place the mesh's footprints at the track's, or change /track/sleepers";
    throw std::invalid_argument(m.str());
  }
}

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
