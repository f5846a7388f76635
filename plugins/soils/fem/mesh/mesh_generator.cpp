#include "mesh/mesh_generator.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "mesh/gmsh_model.hpp"
#include "mesh/mesh_memory.hpp"
#include "mesh/node_order.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

namespace {

bool inside_domain(const MeshPlan& p, double x, double y, double depth) {
  if (depth < 0.0 || depth > p.depth()) return false;
  const double margin = p.radius + p.pml;
  if (p.shape == MeshShape::kBox)
    return x >= p.region.x0 - margin && x <= p.region.x1 + margin && y >= p.region.y0 - margin &&
           y <= p.region.y1 + margin;
  const double dx = x - p.region.centre_x(), dy = y - p.region.centre_y();
  return dx * dx + dy * dy + depth * depth <= p.radius * p.radius;
}

bool inside_layer(const MeshPlan& p, double x, double y, double depth) {
  return p.pml > 0.0 && !p.physical_box(0.5, 0.0).inside_physical_box({x, y, depth});
}

/// Integral of 0.8 / h^3 over the domain (gmsh's HXT makes about 0.8 V / h^3 nodes for a size
/// h, docs/fem-soil.md §2), on a 64 x 64 x 32 midpoint grid: a few per cent, enough to refuse a
/// mesh that would not fit before spending minutes on it. What the grid cannot see is added in
/// closed form: a matched layer thinner than a grid cell (its volume at its own size, the smaller
/// of h_pml and the size where it begins), and as lower bounds the zone within near_distance of the
/// footprints at h_near and the footprints' surface alone (about 1.15 A / h_near^2 nodes:
/// equilateral triangles of side h_near).
double estimate_nodes(const MeshPlan& p) {
  const double margin = p.radius + p.pml;
  const double x0 = p.region.x0 - margin, x1 = p.region.x1 + margin;
  const double y0 = p.region.y0 - margin, y1 = p.region.y1 + margin;
  constexpr int kN = 64, kNz = 32;
  const double dx = (x1 - x0) / kN, dy = (y1 - y0) / kN, dz = p.depth() / kNz;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kNz; ++k) {
        const double x = x0 + (i + 0.5) * dx, y = y0 + (j + 0.5) * dy, z = (k + 0.5) * dz;
        if (!inside_domain(p, x, y, z) || inside_layer(p, x, y, z)) continue;
        const double h = p.size_at(x, y, z);
        sum += 0.8 / (h * h * h);
      }
  double nodes = sum * dx * dy * dz;
  if (p.pml > 0.0) {
    const double lx = p.region.x1 - p.region.x0 + 2.0 * p.radius;
    const double ly = p.region.y1 - p.region.y0 + 2.0 * p.radius;
    const double outer = (lx + 2.0 * p.pml) * (ly + 2.0 * p.pml) * p.depth();
    const double h = std::min(p.h_pml, p.size_at(p.region.x1 + p.radius, p.region.centre_y(), 0.0));
    nodes += 0.8 * (outer - lx * ly * p.radius) / (h * h * h);
  }
  // The zone within near_distance of the footprints, at h_near, may be thinner than the grid's
  // cells too (radius 1000 m, near_distance 0.1 m: estimated 7e4 DOFs, and gmsh ran for minutes).
  const double near = std::min(p.near_distance, p.radius);
  const double near_volume =
      (p.region.x1 - p.region.x0 + 2.0 * near) * (p.region.y1 - p.region.y0 + 2.0 * near) * near;
  const double h3 = p.h_near * p.h_near * p.h_near;
  return std::max({nodes, 0.8 * near_volume / h3, 1.15 * p.footprint_area / (p.h_near * p.h_near)});
}

}  // namespace

double MeshPlan::size_at(double x, double y, double depth) const {
  const double d = region.distance(x, y, depth);
  const double h = std::min(h_max, d <= near_distance ? h_near : h_near * d / near_distance);
  if (pml > 0.0 && !physical_box(0.5, 0.0).inside_physical_box({x, y, depth}))
    return std::min(h, h_pml);
  return h;
}

PmlProfile MeshPlan::physical_box(double reflection, double shift) const {
  return {.low = {region.x0 - radius, region.y0 - radius, 0.0},
          .high = {region.x1 + radius, region.y1 + radius, radius},
          .thickness = pml,
          .reflection = reflection,
          .shift = shift};
}

double MeshPlan::resolved_frequency(double d, double c_r, double elements_per_wavelength) const {
  const double h = size_at(region.x1 + d, region.centre_y(), 0.0);  // on the ground
  return c_r / (h * elements_per_wavelength);
}

MeshPlan plan_mesh(const FemSettings& s, const std::vector<Footprint>& footprints) {
  if (footprints.empty()) throw std::invalid_argument("fem: the track announced no footprints");
  MeshPlan p;
  p.region = TrackRegion::of(footprints);
  for (const Footprint& f : footprints) p.footprint_area += f.length * f.width;
  p.shape = s.mesh.shape;
  p.radius = s.mesh.radius;
  p.near_distance = s.mesh.near_distance;
  p.refine = s.mesh.refine;
  const double c_r = soils::slowest_wave_speeds(s.layers, s.half_space).rayleigh;
  p.h_near =
      s.mesh.h_near > 0.0 ? s.mesh.h_near : c_r / (s.mesh.f_max * s.mesh.elements_per_wavelength);
  p.h_max = s.mesh.h_max > 0.0 ? s.mesh.h_max : std::max(p.h_near, p.radius / 4.0);
  if (s.boundary.kind == BoundaryKind::kPml) {
    p.pml = s.boundary.pml_thickness;
    p.h_pml = p.pml / s.boundary.pml_elements;
  }
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
      << peak_bytes_per_million_dofs() * 1e-9 << " GB per million DOFs at a run's peak)";
    throw std::invalid_argument(m.str());
  }
  check_memory_for(3.0 * p.estimated_nodes, "fem: params/mesh",
                   "lower mesh.f_max or mesh.radius, raise mesh.h_near");
  return p;
}

TetMesh generate_mesh(const FemSettings& s, const std::vector<Footprint>& footprints,
                      const MeshPlan& p) {
  namespace occ = gmsh::model::occ;
  GmshSession session(s.mesh_threads);
  // gmsh's frame has z up (ground at z = 0, soil below); the mesh is returned with z down.
  const double xc = p.region.centre_x(), yc = p.region.centre_y(), R = p.radius;
  const double margin = R + p.pml;  // the box's, with its matched layer
  const double bx0 = p.region.x0 - margin, by0 = p.region.y0 - margin;
  const double bdx = p.region.x1 - p.region.x0 + 2.0 * margin;
  const double bdy = p.region.y1 - p.region.y0 + 2.0 * margin;
  gmsh_call("build the geometry", [&] {
    const int volume = p.shape == MeshShape::kHemisphere
                           ? occ::addSphere(xc, yc, 0.0, R, -1, -std::numbers::pi / 2.0, 0.0,
                                            2.0 * std::numbers::pi)
                           : occ::addBox(bx0, by0, -p.depth(), bdx, bdy, p.depth());
    gmsh::vectorpair tools;
    for (const Footprint& f : footprints)
      tools.emplace_back(
          2, occ::addRectangle(f.x - 0.5 * f.width, f.y - 0.5 * f.length, 0.0, f.width, f.length));
    double bottom = 0.0;
    for (const soils::SoilLayer& l : s.layers) {
      bottom += l.thickness;
      if (bottom >= p.depth()) break;
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
    // mesh.refine: gmsh meshes coarser by 2^refine, and the refinements bring the sizes back.
    const double scale = p.coarse_scale();
    gmsh::option::setNumber("Mesh.MeshSizeMax", scale * p.h_max);
    // Delaunay gives the same mesh for the same input; HXT is 2-5x faster but not reproducible
    // from run to run (measured with gmsh 4.8, even on one thread).
    gmsh::option::setNumber("Mesh.Algorithm3D", s.mesh.fast_algorithm ? 10 : 1);
    gmsh::option::setNumber("Mesh.OptimizeThreshold", s.mesh.quality_threshold);
    gmsh::model::mesh::setSizeCallback([&p, scale](int, int, double x, double y, double z) {
      return scale * p.size_at(x, y, -z);
    });
    gmsh::model::mesh::generate(3);
    return 0;
  });

  TetMesh mesh = read_model(s);
  if (mesh.tets.empty()) throw std::runtime_error("fem: gmsh made no tetrahedra");
  order_nodes_spatially(mesh);
  return mesh;
}

}  // namespace rumble::fem
