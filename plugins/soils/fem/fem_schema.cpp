// The FEM soil's params schema (JSON Schema draft 7): the one place that declares each
// parameter's name, type, unit, range and default (E, nu, rho and the layers from
// soil_params.hpp). The host validates the user's params against it and then fills every default
// it declares; read_settings (fem_settings.cpp) reads the result. A setting that only one value
// of another key uses (boundary.pml, boundary.alpha_normal, damping.mechanisms) is refused by an
// if/else here, on the params as the user wrote them, and gets its default only with that value.
#include "fem_schema.hpp"

#include <string>

#include "soil_params.hpp"

namespace rumble::fem {

namespace {

// The layers' own key: the name a mesh file's physical volume gives the layer.
constexpr const char* kLayerName = R"schema(,
          "name": {"type": "string", "minLength": 1, "pattern": "^[A-Za-z][A-Za-z0-9_.-]*$", "description": "the layer's name: the physical volume of a user's mesh file (mesh.file) that has this layer's material; unique, not half_space"})schema";

// The mesh: generated (its sizes, limits and gmsh's options), or a user's file; its export.
std::string mesh_schema() {
  return R"schema(    "mesh": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "the tetrahedral mesh, generated with gmsh when the track announces its footprints (docs/fem-soil.md)",
      "properties": {
        "export": {"type": "string", "minLength": 1, "not": {"pattern": "^/|(^|/)\\.\\.(/|$)", "description": "is absolute or climbs out with '..'; )schema" +
         std::string(kExportRule) +
         R"schema("}, "description": "writes the soil's own mesh as a gmsh file (binary MSH 4.1) with the physical groups mesh.file reads, so that it can be edited in gmsh and used again, at this path inside the run's results directory (outputs.directory, or --output DIR): relative to it, without '..', its folders made; written by rumble run and rumble mesh (rumble mesh SCENARIO --set /soil/params/mesh/export='\"soil.msh\"' writes DIR/soil.msh), never by rumble validate; a new file: anything already at the path is left alone and refused (docs/fem-soil.md section 2.1); not with mesh.file"},
        "file": {"type": "string", "minLength": 1, "description": "a gmsh mesh file (.msh, formats 2.2 and 4.1) to use instead of meshing, relative to the scenario's folder (docs/fem-soil.md section 2): linear tetrahedra only, z up with the ground at z = 0, and the physical groups: surface \"ground\" (the free surface), surface \"footprints\" (the track's footprint rectangles embedded in the ground, one connected patch each, matching the track's footprints in number, centre and size to 2 % of the smaller side or 1 mm), surface \"absorbing\" (the truncation surface, where the boundary acts); optionally volumes named for the layers (a layer's name, layer_<k> with k = 0 the top layer, half_space below the layers; unnamed: layers by depth). The domain must be convex around the footprints. Refused at validation when a group is missing, with the groups the file has. At most 256 bytes per mesh.max_dofs (64 MiB at least), and at most mesh.max_dofs DOFs. The other mesh keys are then ignored"},
        "shape": {"enum": ["hemisphere", "box"], "default": "hemisphere", "description": "truncation of the half-space: a hemisphere centred under the footprints (waves meet its surface near normal incidence, where the absorbing boundary works best), or a box around them"},
        "radius": {"type": "number", "minimum": 1, "maximum": 1000, "default": 20, "description": "hemisphere radius, or the box's margin beyond the footprints on each side and below [m]; put it at least one Rayleigh wavelength of the lowest frequency of interest beyond the farthest receiver; [1, 1000] m: ground vibration from trains is assessed within some 100 m of the track"},
        "f_max": {"type": "number", "minimum": 1, "maximum": 2000, "default": 80, "description": "highest frequency resolved near the track [Hz]; [1, 2000] Hz: ground vibration from trains is 1 to some 250 Hz, ground-borne noise up to about 1 kHz"},
        "elements_per_wavelength": {"type": "number", "minimum": 4, "maximum": 40, "default": 10, "description": "linear tetrahedra per Rayleigh wavelength at f_max near the track (8-10 classic; 15-20 for waveform phase at tens of metres, docs/fem-soil.md section 2) [-]; [4, 40]: fewer than 4 do not carry the wave, more than 40 cost without gain"},
        "near_distance": {"type": "number", "minimum": 0.1, "maximum": 1000, "default": 5, "description": "full resolution within this distance of the footprints [m]; beyond it the size grows in proportion to the distance (f_max resolved falls as near_distance / distance); [0.1, 1000] m: from a footprint's size to mesh.radius's largest (ground vibration is assessed within some 100 m)"},
        "h_near": {"type": "number", "minimum": 0.01, "maximum": 100, "description": "element size near the track [m]; default: slowest Rayleigh speed / (f_max x elements_per_wavelength); [0.01, 100] m: a sleeper's footprint is 0.26 m wide; the mesh's size is bounded apart (mesh.max_dofs)"},
        "h_max": {"type": "number", "minimum": 0.01, "maximum": 1000, "description": "largest element size [m], >= h_near; default radius / 4; [0.01, 1000] m: from h_near's smallest to mesh.radius's largest"},
        "max_dofs": {"type": "number", "minimum": 1000, "maximum": 1e9, "default": 3e6, "description": "largest mesh accepted, in degrees of freedom (3 per node), estimated before meshing; about 1.5 GB per million DOFs at a run's peak (docs/fem-soil.md §7.2), and a mesh that would not fit in the memory available now is refused before meshing; [1e3, 1e9]: 1e9 DOFs would need more than a terabyte"},
        "algorithm": {"enum": ["delaunay", "hxt"], "default": "delaunay", "description": "gmsh's 3D algorithm: delaunay gives the same mesh for the same input on every run; hxt is 2-5x faster on large meshes but its mesh differs slightly from run to run"},
        "threads": {"type": "integer", "minimum": 1, "maximum": 64, "default": 1, "description": "gmsh meshing threads (used by hxt); [1, 64]: a machine's cores"},
        "quality_threshold": {"type": "number", "minimum": 0, "maximum": 0.95, "default": 0.3, "description": "gmsh optimizes the tetrahedra whose quality is below this (its Mesh.OptimizeThreshold) [-]: the worst tetrahedra set the explicit stable step; 0.6 gave a 20 % longer step than gmsh's 0.3 on the stiff example for about the same meshing time, 0.9 no more for 3x the time (docs/fem-soil.md section 2); [0, 0.95]: gmsh's quality is 0 to 1, 1 only for the regular tetrahedron, which no mesh reaches everywhere"},
        "refine": {"type": "integer", "minimum": 0, "maximum": 3, "default": 0, "description": "uniform refinements of the generated mesh [-]: gmsh meshes at 2^refine times the sizes of the mesh-size rule, and each tetrahedron is cut into 8 by its edge midpoints, refine times, which gives about the mesh of the rule (the estimate, mesh.max_dofs and the memory checks are of the refined mesh) in a fraction of gmsh's time; the surfaces stay the coarse mesh's: exact for the box and the flat ground, a hemisphere's truncation surface faceted at the coarse size (docs/fem-soil.md section 2); [0, 3]: 3 is 512 tetrahedra per coarse one; ignored with mesh.file"}
      }
    })schema";
}

// The truncation surface: its kind, the matched layer, the springs.
std::string boundary_schema() {
  return R"schema(    "boundary": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "the truncation surface",
      "properties": {
        "type": {"enum": ["viscous_spring", "dashpot", "fixed", "pml"], "default": "viscous_spring", "description": "viscous_spring: Lysmer-Kuhlemeyer dashpots rho c_p (normal) and rho c_s (tangential) per unit area plus springs (boundary.springs), which hold the static load without drift; dashpot: the dashpots alone (the static state comes from the springs, the dynamics have no static support: a net force drifts); fixed: no motion (reflects every wave, for checks); pml: a perfectly matched layer of boundary.pml.thickness beyond the box's sides and bottom (mesh.shape box, explicit integrator), which absorbs waves of any incidence above a few Hz (17 times less reflected than the viscous-spring boundary on the same box, 4 times less than on a box of the same DOFs, which costs 12 times less per simulated second: docs/fem-soil.md section 3.1), fixed behind; its damping may shorten the explicit step (logged)"},
        "pml": {
          "type": "object", "additionalProperties": false,
          "description": "the perfectly matched layer (boundary.type pml only: refused under the other types, which would ignore it; its defaults are filled only with pml)",
          "properties": {
            "thickness": {"type": "number", "minimum": 0.5, "maximum": 1000, "description": "thickness of the layer beyond the box [m], added to the mesh outside mesh.radius; default mesh.radius / 2; [0.5, 1000] m: a layer absorbs waves as long as about its thickness (4 m above a few Hz on a medium soil, docs/fem-soil.md section 3.1); as mesh.radius's at most"},
            "reflection": {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1, "default": 0.01, "description": "continuum reflection coefficient of a P wave at normal incidence [-]: sets the damping profile d = d0 (x / thickness)^2, d0 = 3 c_p ln(1 / R) / (2 thickness); lower values gain little on a discrete layer (the elements' own reflection dominates) and shorten the explicit step (d0 dt <= 0.4); (0, 1): 0 would need an infinite damping, 1 is no layer"},
            "elements": {"type": "number", "minimum": 2, "maximum": 40, "default": 8, "description": "tetrahedra across the layer at least: the element size in the layer is at most thickness / elements (measured: 4 reflect 5 times more than 8, 12 a quarter less) [-]; [2, 40]: fewer than 2 are no profile, more than 40 cost without gain"}
          }
        },
        "far_field": {"enum": ["follows", "static"], "default": "follows", "description": "with springs half_space: follows: in the motion the far field's traction follows the footprint forces' change from the static state through a first-order lag of tau = mean boundary distance / c_s, so a load change settles to the half-space's static state (0.1-1.5 % off 0.5 s after the wheel's load doubles on a 12 m hemisphere); static: it stays at the statics', and a change settles through the springs alone (7-13 % too soft beside a load 5 m off the centre), which is what the linear matrices (the monolithic coupler) describe: use it to compare a co-simulation with the monolithic one to the digit. docs/fem-soil.md section 3.2"},
        "springs": {"enum": ["half_space", "liu"], "default": "half_space", "description": "the static support of viscous_spring and dashpot: half_space: the statics take the traction that the half-space beyond the truncation surface exerts under the footprints' load (Boussinesq's point load integrated over each footprint), so the static state is the half-space's under any load (measured 0.2-1.5 % off Love's closed form at 2.5 and 5 m of a 30-sleeper track under the paper's wheel on a 12 m hemisphere, against up to 13.5 % too soft with liu), and each boundary node gets the 3 x 3 spring that holds the half-space's field of a uniform pressure on the footprints exactly, with alpha_tangential G / r across it (in the motion, see far_field); liu: alpha_normal G / r along the normal and alpha_tangential G / r along the tangents (Liu et al. 2006), no far field: docs/fem-soil.md section 3.2"},
        "alpha_normal": {"type": "number", "minimum": 0, "maximum": 10, "description": "springs liu only (refused with half_space, which would ignore it; default 4/3 with liu): normal spring factor alpha_N [-] of K_N = alpha_N G / r [N/m^3], r the distance from the footprints; [0, 10]: Liu et al. (2006) give 4/3 (0.5 to 2 in the literature)"},
        "alpha_tangential": {"type": "number", "minimum": 0, "maximum": 10, "default": 0.6666666666666666, "description": "tangential spring factor alpha_T [-] of K_T = alpha_T G / r [N/m^3] (springs liu: along the tangents; half_space: across the half-space's static field); [0, 10]: Liu et al. (2006) give 2/3 (0.5 to 2 in the literature)"}
      },
      "allOf": [
        {"if": {"required": ["type"], "properties": {"type": {"const": "pml"}}},
         "then": {"properties": {"pml": {"default": {}}}},
         "else": {"properties": {"pml": {"not": {"description": "sets the perfectly matched layer, but boundary.type is not \"pml\" (the layer would be ignored); set boundary.type \"pml\" or drop boundary.pml"}}}}},
        {"if": {"required": ["springs"], "properties": {"springs": {"const": "liu"}}},
         "then": {"properties": {"alpha_normal": {"default": 1.3333333333333333}}},
         "else": {"properties": {"alpha_normal": {"not": {"description": "sets Liu's normal springs, but boundary.springs is \"half_space\" (springs fitted to the half-space's static field: docs/fem-soil.md section 3.2); set boundary.springs \"liu\" or drop alpha_normal"}}}}}
      ]
    })schema";
}

// Material damping: Rayleigh's terms or the Maxwell mechanisms.
std::string damping_schema() {
  return R"schema(    "damping": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "material damping with the given ratio at f_low and f_high: Rayleigh's C = a0 M + a1 K (below and above them the ratio grows, between them it dips: docs/physics.md §3), or generalized Maxwell mechanisms whose ratio is flat over the band (docs/fem-soil.md section 4.4)",
      "properties": {
        "model": {"enum": ["rayleigh", "maxwell"], "default": "rayleigh", "description": "rayleigh: C = a0 M + a1 K; its a1 K, taken half a step late, shortens the explicit step and rules out local steps on stiff soils; maxwell: memory variables (generalized Maxwell mechanisms, as seismology's constant-Q) with the ratio within 3-4 % of damping.ratio from f_low to f_high and falling outside; E is then the modulus at the band's centre sqrt(f_low f_high), where the soil is E (1 + 2 i ratio); the static modulus is lower (by 7 % at 2 % damping over 5-100 Hz) and the stable step 4 % shorter than undamped, where Rayleigh's may be 30 % shorter or more on fine elements"},
        "mechanisms": {"type": "integer", "minimum": 1, "maximum": 8, "description": "maxwell only (refused with rayleigh, which would ignore it; default 3 with maxwell): mechanisms over the band (3 keep the ratio within 3-4 % up to 1.3 decades, 4 up to 2.3 decades); each adds 3 floats per node to the state and to each step's traffic; [1, 8]: about one per half decade of the band, so 8 cover some 4 decades, more than any band of interest"},
        "ratio": {"type": "number", "minimum": 0, "maximum": 0.5, "default": 0.02, "description": "damping ratio at f_low and f_high [-] (soils: 0.02-0.05); it also removes the mesh's shortest waves, which do not travel to the absorbing boundary (their group velocity is near zero) and would ring on after an abrupt load; 0: none; [0, 0.5]: soils are 0.01 to 0.1, half of critical damping is far beyond any"},
        "f_low": {"type": "number", "minimum": 0.1, "maximum": 10000, "default": 5, "description": "lower anchor frequency [Hz] (maxwell: the band's lower end); [0.1, 1e4] Hz: around the band of interest, 1 Hz to mesh.f_max (at most 2 kHz)"},
        "f_high": {"type": "number", "minimum": 0.1, "maximum": 10000, "default": 100, "description": "upper anchor frequency [Hz], > f_low (maxwell: the band's upper end); [0.1, 1e4] Hz: around the band of interest, 1 Hz to mesh.f_max (at most 2 kHz)"}
      },
      "if": {"required": ["model"], "properties": {"model": {"const": "maxwell"}}},
      "then": {"properties": {"mechanisms": {"default": 3}}},
      "else": {"properties": {"mechanisms": {"not": {"description": "sets the Maxwell mechanisms, but damping.model is \"rayleigh\"; set damping.model \"maxwell\" or drop damping.mechanisms"}}}}
    })schema";
}

// The time stepping inside each macro step.
std::string integrator_schema() {
  return R"schema(    "integrator": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "time stepping inside each macro step",
      "properties": {
        "scheme": {"enum": ["explicit", "implicit"], "default": "explicit", "description": "explicit: central differences at courant x the stable step (one pass over K per step; the right choice on wave-resolving meshes, docs/numerics.md §1); implicit: Newmark average acceleration (unconditionally stable, one CHOLMOD factor per step size, under mpirun MUMPS's over the ranks; pays only when a few elements are far smaller than the waves need)"},
        "max_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "implicit: longest sub-step [s]; default 1 / (20 mesh.f_max), 20 steps per period at f_max (period error about 0.8 %); [1e-7, 1] s: as time.macro_step's (20 steps per period of 2 kHz, the highest mesh.f_max, are 2.5e-5 s)"},
        "local_steps": {"type": "integer", "minimum": 1, "maximum": 8, "default": 1, "description": "explicit: local time stepping; the stiffest nodes (where a few short elements set the stable step) take this many steps per soil step, the rest one, so the soil step can be longer (docs/fem-soil.md section 4.1); the soil chooses those nodes and the step at the first macro step (a step that makes fewer whole sub-steps of it), verifies the step by the largest eigenvalue of its operator and logs the gain, and stays on one rate where none pays; 1: one rate everywhere; 2 gave all the gain on the meshes measured (1.2-1.3x per simulated second at 1e6 DOFs; 3 cost more than it saved); [1, 8]: more rates would not pay, 3 already did not"},
        "precision": {"enum": ["single", "double"], "default": "single", "description": "explicit: how the step reads the stiffness matrix, the stream that bounds its speed; single: its values rounded to float (each moves by at most 6e-8 of itself, far below the step's own error; the state and the sums stay double; 1.4x faster at 3e5 DOFs, docs/fem-soil.md section 4.2); double: as assembled; the statics, the implicit step and the LU receptance always use double"}
      }
    })schema";
}

// How the footprint receptance is computed.
std::string receptance_schema() {
  return R"schema(    "receptance": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "the footprint receptance H(f) (rumble soil-frf, rumble calibrate; docs/fem-soil.md section 5)",
      "properties": {
        "method": {"enum": ["lu", "impulse"], "default": "lu", "description": "lu: one complex sparse LU of the whole mesh per frequency (exact for the mesh; 3.5 s at 2e4 DOFs, 13 minutes at 1.6e5); impulse: one explicit run per footprint, loaded by a short pulse, gives every frequency at once (from about 1e5 DOFs or a dozen frequencies on, far cheaper; its band ends near 3 mesh.f_max, and what the record cuts off is its error at low frequency)"},
        "duration": {"type": "number", "exclusiveMinimum": 0, "maximum": 60, "default": 2, "description": "impulse: the record of each run [s]; it must outlast the response (warned when the motion in its last tenth exceeds 1 % of its peak); (0, 60] s: a footprint's response dies out within a second or two; at least 2 / mesh.f_max, checked apart"}
      }
    })schema";
}

// The static state's solver above the factor limit (docs/fem-soil.md §7.1).
std::string statics_schema() {
  return R"schema(    "statics": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "the static state each run starts from (docs/fem-soil.md section 7.1)",
      "properties": {
        "solver": {"enum": ["auto", "gamg", "geometric", "aggregation"], "x-removed": {"multigrid": "(the soil's own multigrid) was removed on 2026-12-06: \"auto\" replaces it, PETSc's GAMG or the geometric multigrid (docs/decisions/0018-petsc-statics.md)"}, "default": "auto", "description": "above 4e5 DOFs, where a CHOLMOD factor would take several GB (below, the factor solves whatever this says), PETSc's conjugate gradients (PETSc and MPI start then) preconditioned by: auto: geometric where mesh.refine is 1 or more and the mesh is generated, else gamg on one process and aggregation under mpirun; under mpirun -n N (N > 1) rank 0 factors below the limit and the N ranks solve above it; gamg: PETSc's algebraic multigrid GAMG set up from K + S (in K's own rows, no copy), CG's products and the finest smoothing by the step's own threaded product (K as the step reads it), plain aggregation: 78 iterations and a static start of 27-28 s at 8.8e5 DOFs, 1.3 kB per DOF; geometric: a two-level geometric multigrid on mesh.refine's nested meshes (needs mesh.refine 1 or more and a generated mesh): the soil's mesh matrix-free, gmsh's coarse mesh assembled and solved by GAMG, so the statics hold no assembled fine matrix: the fastest and smallest (docs/fem-soil.md section 7.1); aggregation: under mpirun, a two-level multigrid on the ranks with no assembled fine matrix: the soil's mesh matrix-free, its first level by plain aggregation of each rank's nodes and the rigid-body modes, its coarse matrix summed element by element and solved by GAMG (on one process: gamg, which holds no copy of K there; docs/fem-soil.md section 8); gamg, geometric and aggregation named: under mpirun solved on the N ranks at any size (docs/fem-soil.md section 8); the former multigrid (the soil's own) was removed on 2026-12-06: auto replaces it (docs/decisions/0018-petsc-statics.md)"}
      }
    })schema";
}

// The explicit step's fraction of the stable step.
std::string courant_schema() {
  return R"schema(    "courant": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.9, "description": "the explicit step as a fraction of the stable step 2 / omega_max, omega_max the largest eigenfrequency of the mesh (Lanczos iterations) [-]; (0, 1]: beyond 1 the central differences diverge"})schema";
}

}  // namespace

const char* settings_schema() {
  static const std::string schema =
      R"schema({
  "$schema": "http://json-schema.org/draft-07/schema#",
  "type": "object",
  "additionalProperties": false,
  "required": ["E", "nu", "rho"],
  "properties": {
)schema" +
      soils::soil_properties_schema(
          "horizontal layers over the half-space, top first, meshed as "
          "they are: element faces follow each interface",
          kLayerName) +
      ",\n" + mesh_schema() + ",\n" + boundary_schema() + ",\n" + damping_schema() + ",\n" +
      integrator_schema() + ",\n" + receptance_schema() + ",\n" + statics_schema() + ",\n" +
      courant_schema() + R"schema(
  }
})schema";
  return schema.c_str();
}

}  // namespace rumble::fem
