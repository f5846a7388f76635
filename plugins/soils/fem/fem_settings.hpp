// The FEM soil's settings as typed values, read once from its params (the host has validated
// them against fem_schema.hpp and filled the defaults): the soil profile, the mesh request, the
// absorbing boundary, material damping and the explicit step's safety factor. SI units.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "half_space.hpp"
#include "layered_soil.hpp"
#include "maxwell_damping.hpp"

namespace rumble::fem {

enum class MeshShape { kHemisphere, kBox };

/// Lysmer-Kuhlemeyer dashpots with springs (viscous-spring boundary, Liu et al. 2006: static
/// support, no drift), dashpots only (the static state then comes from the springs and the
/// dynamics see no static support), a fixed truncation surface (reflects everything), or a
/// perfectly matched layer around a box (pml.hpp) with a fixed surface behind it.
enum class BoundaryKind { kViscousSpring, kDashpot, kFixed, kPml };
/// The boundary springs: fitted to the half-space's static field (docs/fem-soil.md section 3.2)
/// or Liu et al.'s alpha G / r.
enum class SpringModel { kHalfSpace, kLiu };

struct MeshRequest {
  MeshShape shape = MeshShape::kHemisphere;
  double radius = 20.0;                 // m: hemisphere radius, or the box's margin
  double f_max = 80.0;                  // Hz resolved near the track
  double elements_per_wavelength = 10;  // linear tetrahedra per Rayleigh wavelength at f_max
  double near_distance = 5.0;           // m: full resolution within this distance of the track
  double h_near = 0.0;                  // m: 0 = from f_max and the slowest Rayleigh speed
  double h_max = 0.0;                   // m: cap of the element size far away; 0 = radius / 4
  double max_dofs = 3e6;                // refused before meshing beyond this estimate
  bool fast_algorithm = false;          // gmsh HXT (fast, not reproducible) instead of Delaunay
  /// gmsh optimizes the tetrahedra whose quality (gamma) is below this [-]: gmsh's own 0.3 by
  /// default; 0.6 lengthened the stable step 20 % on the stiff example (docs/fem-soil.md §2).
  double quality_threshold = 0.3;
  std::string file;         // a user's .msh instead (as given: relative to the scenario)
  std::string export_file;  // where to write the generated mesh as .msh, inside the run's
                            // results directory ("" none; as given: relative, no "..")
  /// The largest mesh file read [bytes]: about 100 B per DOF as ASCII .msh, so 256 B per
  /// mesh.max_dofs, at least 64 MiB.
  double max_file_bytes() const { return std::max(64.0 * 1048576.0, 256.0 * max_dofs); }
};

struct BoundaryRequest {
  BoundaryKind kind = BoundaryKind::kViscousSpring;
  SpringModel spring_model = SpringModel::kHalfSpace;
  /// kHalfSpace: the far field's traction follows the footprint forces in the motion (lagged,
  /// docs/fem-soil.md §3.2); false ("static"): held at the statics', as the linear matrices are.
  bool far_field_follows = true;
  double alpha_normal = 4.0 / 3.0;      // kLiu: spring K_N = alpha_N G / r per unit area [-]
  double alpha_tangential = 2.0 / 3.0;  // spring K_T = alpha_T G / r per unit area [-], kLiu's
                                        // tangents and kHalfSpace's directions across the field
  // kPml: the layer beyond the box's sides and bottom.
  double pml_thickness = 0.0;        // m; 0 = mesh.radius / 2
  double pml_reflection = 1e-2;      // [-] continuum reflection of a normally incident P wave
  double pml_elements = 8;           // tetrahedra across the layer, at least (sizes its mesh)
  double pml_shift_frequency = 5.0;  // Hz: alpha = 2 pi f, the stretching's frequency shift
  double pml_shift() const;          // alpha [1/s]
  /// Whether the truncation surface has the viscous-spring blocks (springs included).
  bool springs() const { return kind == BoundaryKind::kViscousSpring; }
};

/// Material damping with the ratio `ratio` at f_low and f_high: Rayleigh's C = a0 M + a1 K
/// (docs/physics.md §3), or generalized Maxwell mechanisms flat over the band between them
/// (maxwell_damping.hpp), with E the modulus at the band's centre sqrt(f_low f_high).
struct DampingRequest {
  double ratio = 0.02;                   // [-]; 0: no material damping
  double f_low = 5.0, f_high = 100.0;    // Hz
  bool maxwell = false;                  // the mechanisms instead of Rayleigh's terms
  int mechanisms = 3;                    // maxwell: how many
  double mass_coefficient() const;       // a0 [1/s] (0 with the mechanisms)
  double stiffness_coefficient() const;  // a1 [s] (0 with the mechanisms)
  /// The mechanisms (maxwell), none otherwise.
  MaxwellDamping maxwell_mechanisms() const;
  /// The relaxed (static) modulus over E [-]: 1 under Rayleigh; with the mechanisms
  /// 1 / Re(modulus) at the band's centre, so that the soil is E (1 + 2 i ratio) there.
  double relaxed_modulus_factor() const;
};

/// How the footprint receptance is computed: one complex LU per frequency (exact for the mesh),
/// or one explicit run per footprint (impulse_receptance.hpp: all frequencies at once).
struct ReceptanceRequest {
  bool impulse = false;
  double duration = 2.0;  // s: the impulse responses' record
};

struct FemSettings {
  soils::SoilProperties half_space;
  std::vector<soils::SoilLayer> layers;  // top first
  std::vector<std::string> layer_names;  // per layer: its "name", "" when none
  MeshRequest mesh;
  BoundaryRequest boundary;
  DampingRequest damping;
  ReceptanceRequest receptance;
  double courant = 0.9;        // explicit step = courant x the stable step from the mesh
  bool implicit = false;       // Newmark average acceleration instead of central differences
  double implicit_step = 0.0;  // s, longest implicit sub-step; 0 = 1 / (20 f_max)
  int local_steps = 1;         // explicit: sub-steps of the stiffest nodes per step; 1 = one rate
  bool single_precision_step = true;  // explicit: the step reads K's values as float
  unsigned mesh_threads = 1;

  /// The properties at depth z [m] (>= 0).
  const soils::SoilProperties& properties_at(double depth) const;
};

/// Reads and checks params (JSON text); messages start "fem: params/<key>: ...".
FemSettings read_settings(const std::string& params_json);

/// JSON Schema (draft 7) of the params.
const char* settings_schema();

}  // namespace rumble::fem
