#include "mesh_generator.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "wave_speeds.hpp"

namespace rumble::fem {

namespace {

constexpr double kPi = std::numbers::pi;

/// The gmsh session of one meshing: gmsh keeps global state, so one at a time per process, and
/// gmsh 4.8 throws std::string (toolchain.md §8.10), turned here into std::runtime_error.
class GmshSession {
 public:
  explicit GmshSession(unsigned threads) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::option::setNumber("General.NumThreads", threads);
    // Same input, same mesh: gmsh otherwise takes as many threads as OpenMP offers per stage.
    for (const char* stage :
         {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
      gmsh::option::setNumber(stage, threads);
    gmsh::model::add("soil");
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

template <class F>
auto gmsh_call(const char* what, F&& f) {
  try {
    return f();
  } catch (const std::string& message) {
    throw std::runtime_error(std::string("fem: gmsh failed to ") + what + ": " + message);
  }
}

bool inside_domain(const MeshPlan& p, double x, double y, double depth) {
  if (depth < 0.0 || depth > p.depth()) return false;
  if (p.shape == MeshShape::kBox)
    return x >= p.region.x0 - p.radius && x <= p.region.x1 + p.radius &&
           y >= p.region.y0 - p.radius && y <= p.region.y1 + p.radius;
  const double dx = x - p.region.centre_x(), dy = y - p.region.centre_y();
  return dx * dx + dy * dy + depth * depth <= p.radius * p.radius;
}

/// Integral of 0.8 / h^3 over the domain (gmsh's HXT makes about 0.8 V / h^3 nodes for a size
/// h, numerics.md §1), on a 64 x 64 x 32 midpoint grid: a few per cent, enough to refuse a mesh
/// that would not fit before spending minutes on it.
double estimate_nodes(const MeshPlan& p) {
  const double x0 = p.region.x0 - p.radius, x1 = p.region.x1 + p.radius;
  const double y0 = p.region.y0 - p.radius, y1 = p.region.y1 + p.radius;
  constexpr int kN = 64, kNz = 32;
  const double dx = (x1 - x0) / kN, dy = (y1 - y0) / kN, dz = p.depth() / kNz;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kNz; ++k) {
        const double x = x0 + (i + 0.5) * dx, y = y0 + (j + 0.5) * dy, z = (k + 0.5) * dz;
        if (!inside_domain(p, x, y, z)) continue;
        const double h = p.size_at(x, y, z);
        sum += 0.8 / (h * h * h);
      }
  return sum * dx * dy * dz;
}

}  // namespace

double MeshPlan::size_at(double x, double y, double depth) const {
  const double d = region.distance(x, y, depth);
  return std::min(h_max, d <= near_distance ? h_near : h_near * d / near_distance);
}

double MeshPlan::resolved_frequency(double d, double c_r, double elements_per_wavelength) const {
  const double centre_depth = 0.0;
  const double h = size_at(region.x1 + d, region.centre_y(), centre_depth);
  return c_r / (h * elements_per_wavelength);
}

MeshPlan plan_mesh(const FemSettings& s, const std::vector<Footprint>& footprints) {
  if (footprints.empty()) throw std::invalid_argument("fem: the track announced no footprints");
  MeshPlan p;
  p.region = TrackRegion::of(footprints);
  p.shape = s.mesh.shape;
  p.radius = s.mesh.radius;
  p.near_distance = s.mesh.near_distance;
  const double c_r = soils::slowest_wave_speeds(s.layers, s.half_space).rayleigh;
  p.h_near =
      s.mesh.h_near > 0.0 ? s.mesh.h_near : c_r / (s.mesh.f_max * s.mesh.elements_per_wavelength);
  p.h_max = s.mesh.h_max > 0.0 ? s.mesh.h_max : std::max(p.h_near, p.radius / 4.0);
  if (p.shape == MeshShape::kHemisphere && p.region.half_diagonal() > 0.8 * p.radius) {
    std::ostringstream m;
    m << "fem: params/mesh/radius: the footprints span " << 2.0 * p.region.half_diagonal()
      << " m (corner to corner), too much for a hemisphere of radius " << p.radius
      << " m; give a radius of at least " << std::ceil(p.region.half_diagonal() / 0.8)
      << " m (footprints within 80 % of it) or mesh.shape \"box\"";
    throw std::invalid_argument(m.str());
  }
  p.estimated_nodes = estimate_nodes(p);
  if (3.0 * p.estimated_nodes > s.mesh.max_dofs) {
    std::ostringstream m;
    m.precision(3);
    m << "fem: params/mesh: the mesh would have about " << 3.0 * p.estimated_nodes
      << " degrees of freedom (h_near " << p.h_near << " m, h_max " << p.h_max << " m, radius "
      << p.radius << " m), more than mesh.max_dofs = " << s.mesh.max_dofs
      << "; lower mesh.f_max or mesh.radius, raise mesh.h_near, or raise mesh.max_dofs (about "
      << "1 GB per million DOFs)";
    throw std::invalid_argument(m.str());
  }
  return p;
}

TetMesh generate_mesh(const FemSettings& s, const std::vector<Footprint>& footprints,
                      const MeshPlan& p) {
  namespace occ = gmsh::model::occ;
  GmshSession session(s.mesh_threads);
  // gmsh's frame has z up (ground at z = 0, soil below); the mesh is returned with z down.
  const double xc = p.region.centre_x(), yc = p.region.centre_y(), R = p.radius;
  const double bx0 = p.region.x0 - R, by0 = p.region.y0 - R;
  const double bdx = p.region.x1 - p.region.x0 + 2.0 * R, bdy = p.region.y1 - p.region.y0 + 2.0 * R;
  gmsh_call("build the geometry", [&] {
    const int volume = p.shape == MeshShape::kHemisphere
                           ? occ::addSphere(xc, yc, 0.0, R, -1, -kPi / 2.0, 0.0, 2.0 * kPi)
                           : occ::addBox(bx0, by0, -R, bdx, bdy, R);
    gmsh::vectorpair tools;
    for (const Footprint& f : footprints)
      tools.emplace_back(
          2, occ::addRectangle(f.x - 0.5 * f.width, f.y - 0.5 * f.length, 0.0, f.width, f.length));
    double bottom = 0.0;
    for (const soils::SoilLayer& l : s.layers) {
      bottom += l.thickness;
      if (bottom >= R) break;
      tools.emplace_back(2, occ::addRectangle(bx0 - 1.0, by0 - 1.0, -bottom, bdx + 2.0, bdy + 2.0));
    }
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> out_map;
    occ::fragment({{3, volume}}, tools, out, out_map);
    occ::synchronize();
    // Parts of the interface rectangles outside the volume bound nothing: drop them.
    gmsh::vectorpair surfaces, dangling;
    gmsh::model::getEntities(surfaces, 2);
    for (const auto& [dim, tag] : surfaces) {
      std::vector<int> up, down;
      gmsh::model::getAdjacencies(dim, tag, up, down);
      if (up.empty()) dangling.emplace_back(dim, tag);
    }
    if (!dangling.empty()) {
      occ::remove(dangling, /*recursive=*/true);
      occ::synchronize();
    }
    return 0;
  });

  gmsh_call("mesh the soil", [&] {
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeMax", p.h_max);
    // Delaunay gives the same mesh for the same input; HXT is 2-5x faster but not reproducible
    // from run to run (measured with gmsh 4.8, even on one thread).
    gmsh::option::setNumber("Mesh.Algorithm3D", s.mesh.fast_algorithm ? 10 : 1);
    gmsh::model::mesh::setSizeCallback(
        [&p](int, int, double x, double y, double z) { return p.size_at(x, y, -z); });
    gmsh::model::mesh::generate(3);
    return 0;
  });

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
    const auto node = [&](std::size_t tag) { return index[position.at(tag)]; };
    mesh.tets.resize(tet_tags.size());
    mesh.layer.resize(tet_tags.size());
    for (std::size_t e = 0; e < tet_tags.size(); ++e) {
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
    // Faces of the surfaces that bound one volume only: the ground, or the truncation.
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    const double ground_tolerance = 1e-9 * R;
    for (const auto& [dim, tag] : surfaces) {
      std::vector<int> up, down;
      gmsh::model::getAdjacencies(dim, tag, up, down);
      if (up.size() != 1) continue;
      std::vector<std::size_t> tri_tags, tri_nodes;
      gmsh::model::mesh::getElementsByType(2, tri_tags, tri_nodes, tag);
      for (std::size_t e = 0; e < tri_tags.size(); ++e) {
        const Triangle f{node(tri_nodes[3 * e]), node(tri_nodes[3 * e + 1]),
                         node(tri_nodes[3 * e + 2])};
        const bool on_ground = std::abs(mesh.nodes(2, f[0])) < ground_tolerance &&
                               std::abs(mesh.nodes(2, f[1])) < ground_tolerance &&
                               std::abs(mesh.nodes(2, f[2])) < ground_tolerance;
        (on_ground ? mesh.ground : mesh.truncation).push_back(f);
      }
    }
    return 0;
  });
  if (mesh.tets.empty()) throw std::runtime_error("fem: gmsh made no tetrahedra");
  return mesh;
}

}  // namespace rumble::fem
