// The FEM soil's settings as typed values, read once from its params by read_settings. The params
// schema (fem_schema.cpp, soil_params.hpp) declares each parameter's name, type, unit, range and
// default once; the host validates the params against it and fills every declared default before
// the plugin sees them, so nothing here repeats a default: a member is what the params say, or a
// default derived from other settings where the comment says so. A default-constructed struct is
// all zeros, not a usable setting: the tests build theirs from params too. SI units.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "fem_schema.hpp"
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
  MeshShape shape{};
  double radius{};                   // m: hemisphere radius, or the box's margin
  double f_max{};                    // Hz resolved near the track
  double elements_per_wavelength{};  // linear tetrahedra per Rayleigh wavelength at f_max
  double near_distance{};            // m: full resolution within this distance of the track
  double h_near{};                   // m; derived when not given (0): plan_mesh, from f_max and
                                     // the slowest Rayleigh speed
  double h_max{};                    // m: cap of the element size far away; derived when not
                                     // given (0): plan_mesh, radius / 4
  double max_dofs{};                 // refused before meshing beyond this estimate
  bool fast_algorithm{};             // gmsh HXT (fast, not reproducible) instead of Delaunay
  /// gmsh optimizes the tetrahedra whose quality (gamma) is below this [-] (docs/fem-soil.md §2).
  double quality_threshold{};
  /// Uniform refinements of the generated mesh (docs/fem-soil.md §2): gmsh meshes at 2^refine
  /// times the rule's sizes, each tetrahedron is then cut into 8, refine times.
  int refine{};
  std::string file;         // a user's .msh instead (as given: relative to the scenario)
  std::string export_file;  // where to write the generated mesh as .msh, inside the run's
                            // results directory ("" none; as given: relative, no "..")
  /// The largest mesh file read [bytes]: about 100 B per DOF as ASCII .msh, so 256 B per
  /// mesh.max_dofs, at least 64 MiB.
  double max_file_bytes() const { return std::max(64.0 * 1048576.0, 256.0 * max_dofs); }
};

struct BoundaryRequest {
  BoundaryKind kind{};
  SpringModel spring_model{};
  /// kHalfSpace: the far field's traction follows the footprint forces in the motion (lagged,
  /// docs/fem-soil.md §3.2); false ("static"): held at the statics', as the linear matrices are.
  bool far_field_follows{};
  double alpha_normal{};      // kLiu: spring K_N = alpha_N G / r per unit area [-]; 0 otherwise
  double alpha_tangential{};  // spring K_T = alpha_T G / r per unit area [-], kLiu's tangents
                              // and kHalfSpace's directions across the field
  // kPml: the layer beyond the box's sides and bottom (zeros under the other kinds).
  double pml_thickness{};   // m; derived when not given: mesh.radius / 2 (read_settings)
  double pml_reflection{};  // [-] continuum reflection of a normally incident P wave
  double pml_elements{};    // tetrahedra across the layer, at least (sizes its mesh)
  /// Hz: alpha = 2 pi f, the stretching's frequency shift. Not a parameter: fixed by the
  /// layer's design (docs/fem-soil.md section 3.1).
  double pml_shift_frequency = 5.0;
  double pml_shift() const;  // alpha [1/s]
  /// Whether the truncation surface has the viscous-spring blocks (springs included).
  bool springs() const { return kind == BoundaryKind::kViscousSpring; }
};

/// Material damping with the ratio `ratio` at f_low and f_high: Rayleigh's C = a0 M + a1 K
/// (docs/physics.md §3), or generalized Maxwell mechanisms flat over the band between them
/// (maxwell_damping.hpp), with E the modulus at the band's centre sqrt(f_low f_high).
struct DampingRequest {
  double ratio{};                        // [-]; 0: no material damping
  double f_low{}, f_high{};              // Hz
  bool maxwell{};                        // the mechanisms instead of Rayleigh's terms
  int mechanisms{};                      // maxwell: how many (0 under Rayleigh)
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
  bool impulse{};
  double duration{};  // s: the impulse responses' record
};

struct FemSettings {
  soils::SoilProperties half_space;
  std::vector<soils::SoilLayer> layers;  // top first
  std::vector<std::string> layer_names;  // per layer: its "name", "" when none
  MeshRequest mesh;
  BoundaryRequest boundary;
  DampingRequest damping;
  ReceptanceRequest receptance;
  double courant{};              // explicit step = courant x the stable step from the mesh
  bool implicit{};               // Newmark average acceleration instead of central differences
  double implicit_step{};        // s, longest implicit sub-step; derived when not given:
                                 // 1 / (20 mesh.f_max) (read_settings)
  int local_steps{};             // explicit: sub-steps of the stiffest nodes per step; 1 = one rate
  bool single_precision_step{};  // explicit: the step reads K's values as float
  // Above the factor limit the statics are PETSc's CG with GAMG or with the geometric multigrid
  // on mesh.refine's nested meshes (statics.solver, whose "auto" takes the geometric multigrid
  // where those meshes exist: docs/fem-soil.md §7.1).
  bool geometric_statics{};  // the geometric multigrid, else GAMG
  // Under mpirun without the geometric multigrid: the aggregation multigrid on the unassembled
  // K (statics.solver aggregation, or auto; docs/fem-soil.md §8), else GAMG on PETSc's copy of
  // K + S. One process solves by GAMG either way (its GAMG shares K's rows, §7.1).
  bool aggregation_statics{};
  bool statics_named{};  // statics.solver named, not "auto": under mpirun solved on the
                         // ranks at any size (auto: by rank 0's factor below its limit)
  unsigned mesh_threads{};

  /// The properties at depth z [m] (>= 0).
  const soils::SoilProperties& properties_at(double depth) const;
};

/// Reads params (JSON text) validated against settings_schema(), and checks what the schema
/// cannot say (relations between keys); messages start "fem: params/<key>: ...". A key absent
/// from params reads the schema's default (the host fills them in already; a direct caller of
/// the C API need not), and one with neither is a plugin bug, named as such.
FemSettings read_settings(const std::string& params_json);

}  // namespace rumble::fem
