// Meshing the soil with gmsh (C++ API, OCC kernel) from the settings and the footprints the
// track announces: a hemisphere (or a box) under the footprints, the footprint rectangles and the
// layer interfaces embedded so that element faces follow them, and an element size that is
// h_near within near_distance of the footprints and grows in proportion to the distance beyond
// (docs/numerics.md §2: gentle grading, the frequency resolved falls as near_distance / distance),
// capped by h_max.
#pragma once

#include <cmath>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/pml_profile.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/track_region.hpp"

namespace rumble::fem {

/// The domain and element sizes of a mesh, decided (and checked) before meshing.
struct MeshPlan {
  TrackRegion region;
  MeshShape shape = MeshShape::kHemisphere;
  double radius = 0.0;          // m
  double h_near = 0.0;          // m
  double h_max = 0.0;           // m
  double near_distance = 0.0;   // m
  double estimated_nodes = 0;   // 0.8 V / h^3 integrated over the domain (docs/fem-soil.md §2)
  double pml = 0.0;             // m: a matched layer's thickness beyond the box (sides, bottom)
  double h_pml = 0.0;           // m: the largest element size in the layer
  double footprint_area = 0.0;  // m^2: all footprints together
  /// Uniform refinements after gmsh (mesh.refine): the sizes above and the estimate are the
  /// refined mesh's; gmsh meshes at coarse_scale() times them.
  int refine = 0;
  double coarse_scale() const { return std::ldexp(1.0, refine); }
  double depth() const { return radius + pml; }
  /// The box without its matched layer (box shape only).
  PmlProfile physical_box(double reflection, double shift) const;
  /// Element size [m] requested at (x, y, depth).
  double size_at(double x, double y, double depth) const;
  /// Frequency [Hz] resolved at `elements_per_wavelength` by the size at distance d [m] from the
  /// footprints, for a Rayleigh speed c_r [m/s].
  double resolved_frequency(double d, double c_r, double elements_per_wavelength) const;
};

/// Element sizes from the settings (h_near from the slowest Rayleigh speed), the domain around
/// the footprints, and the size estimate. Throws std::invalid_argument when the footprints do
/// not fit in the hemisphere or the estimate exceeds mesh.max_dofs, with the numbers and the fix.
MeshPlan plan_mesh(const FemSettings& settings, const std::vector<Footprint>& footprints);

/// Meshes the plan with gmsh, at coarse_scale() times its sizes (the mesh before mesh.refine's
/// refinements: refine_uniformly, mesh/uniform_refinement.hpp). Throws std::runtime_error with
/// gmsh's message on failure.
TetMesh generate_mesh(const FemSettings& settings, const std::vector<Footprint>& footprints,
                      const MeshPlan& plan);

}  // namespace rumble::fem
