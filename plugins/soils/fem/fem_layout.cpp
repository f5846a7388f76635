// The FEM soil's layout: everything that happens once when the track announces its footprints
// (the mesh, generated, cached or read; the operators; the report of what was built; the local
// steps' choice at the first macro step), kept apart from the per-step code so that the costly,
// once-per-layout set-up reads as one story.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/pml.hpp"
#include "distributed/rank_plan.hpp"
#include "distributed/split_plan.hpp"
#include "fem_soil.hpp"
#include "memory_model.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/mesh_cache.hpp"
#include "mesh/mesh_generator.hpp"
#include "mesh/mesh_memory.hpp"
#include "mesh/node_order.hpp"
#include "mesh/numbered_refinement.hpp"
#include "operator/elasticity.hpp"
#include "operator/footprint_loads.hpp"
#include "statics/coarse_level.hpp"
#include "statics/static_solver.hpp"
#include "time/implicit_solver.hpp"

namespace rumble::fem {

void FemSoil::accept_layout(const std::vector<rumble::Footprint>& footprints) {
  if (distributed_) return accept_layout_distributed(footprints);
  lay_out_here(footprints);
}

void FemSoil::lay_out_here(const std::vector<rumble::Footprint>& footprints) {
  const auto start = std::chrono::steady_clock::now();
  mesh_here(footprints);
  build_here(footprints, seconds_since(start), start);
}

void FemSoil::mesh_here(const std::vector<rumble::Footprint>& footprints) {
  using namespace rumble::fem;
  receptance_.reset();  // it refers to the operators of the previous layout
  impulse_.reset();
  receptance_key_.reset();
  footprints_ = footprints;
  coarse_mesh_ = {};
  if (settings_.mesh.file.empty()) {
    plan_ = plan_mesh(settings_, footprints);
    host_.info("fem: a mesh of about " + format(3.0 * plan_.estimated_nodes) + " DOFs (h_near " +
               format(plan_.h_near) + " m, h_max " + format(plan_.h_max) + " m, radius " +
               format(plan_.radius) + " m)" +
               (plan_.refine > 0
                    ? ", gmsh meshing at " + format(plan_.coarse_scale()) +
                          " times these sizes, refined " + std::to_string(plan_.refine) + " times"
                    : std::string()));
    report_ranks(plan_.estimated_nodes, "the plan's estimate");
    mesh_ = cached_or_new_mesh();
    if (plan_.refine > 0 && !distributed_) refine_here(footprints);
    if (plan_.refine > 0 && distributed_) {
      host_.info("fem: rank 0 holds gmsh's coarse mesh of " +
                 format(static_cast<double>(mesh_.node_count())) + " nodes, " +
                 format(static_cast<double>(mesh_.tets.size())) +
                 " tetrahedra only; each rank refines its part " + std::to_string(plan_.refine) +
                 " times after the split (mesh.refine, docs/fem-soil.md §8)");
      warn_if_coarse_near_track(footprints);
    }
    export_due_ = !settings_.mesh.export_file.empty();
    export_if_due();
  } else {
    MeshFile file = load_mesh_file(settings_, mesh_file_);
    check_mesh_footprints(file, footprints);
    mesh_ = std::move(file.mesh);
    plan_ = {.region = TrackRegion::of(footprints)};  // sizes unknown: radius 0
    host_.info("fem: mesh read from " + mesh_file_);
  }
  report_split();
}

void FemSoil::build_here(const std::vector<rumble::Footprint>& footprints, double mesh_seconds,
                         std::chrono::steady_clock::time_point start) {
  using namespace rumble::fem;
  weights_ = footprint_weights(mesh_, footprints);
  std::vector<BoundaryNode> boundary = absorbing_boundary(mesh_, settings_, footprints);
  std::vector<char> fixed = held_nodes(mesh_.node_count(), boundary, settings_);
  op_.emplace(assemble_stiffness(mesh_, settings_), lumped_mass(mesh_, settings_),
              std::move(boundary), settings_.boundary.springs(), std::move(fixed),
              settings_.damping.mass_coefficient(), settings_.damping.stiffness_coefficient(),
              host_.threads(),
              settings_.single_precision_step ? StepPrecision::kSingle : StepPrecision::kDouble);
  op_->set_loaded_nodes(loaded_nodes(weights_));  // (the footprints' forces act there only)
  // K's rows may go once the statics are done, and are built again if a later call needs them.
  op_->set_stiffness_source([this] { return assemble_stiffness(mesh_, settings_); });
  op_->set_stop_check(throttled_stop_check());
  if (settings_.damping.maxwell) op_->set_maxwell_damping(settings_.damping.maxwell_mechanisms());
  if (settings_.boundary.kind == BoundaryKind::kPml)
    op_->set_pml(PmlLayer(mesh_, settings_, pml_profile()));
  local_steps_chosen_ = false;  // (at the first macro step, whose length they are fitted to)
  const bool petsc = op_->dofs() > StaticSolver::kFactorLimit;
  // PETSc runs on the MPI the host starts for us (ABI 1.4, docs/decisions/0012): asking for the
  // communicator starts it, and PETSc then neither starts nor finalises MPI itself.
  if (petsc) host_.communicator();
  statics_ = std::make_unique<StaticSolver>(
      op_->soil(), mesh_.nodes, StaticSolver::kFactorLimit,
      settings_.geometric_statics ? CgPreconditioner::kGeometric : CgPreconditioner::kGamg);
  if (settings_.geometric_statics)  // (the coarse level at the first solve: validate needs none)
    statics_->set_coarse_level([this] {
      return coarse_level(coarse_mesh_, mesh_, plan_.refine, settings_, footprints_,
                          op_->soil().fixed());
    });
  if (petsc && settings_.statics_named && settings_.aggregation_statics)
    host_.info(
        "fem: statics.solver \"aggregation\" is the ranks' solver under mpirun; one process "
        "solves by GAMG, set up from K's own rows (no copy of K either way: docs/fem-soil.md "
        "section 8)");
  far_field_.reset();  // (built at the first static solve: validate needs none)
  if (settings_.boundary.spring_model == rumble::fem::SpringModel::kHalfSpace &&
      !settings_.layers.empty() && settings_.boundary.springs())
    host_.info(
        "fem: a layered profile: the statics hold no half-space far field (no closed form), "
        "the boundary springs alone, fitted to the half-space's field with each node's own G "
        "and nu (docs/fem-soil.md section 3.2)");
  implicit_.reset();
  if (settings_.implicit)
    implicit_ = std::make_unique<ImplicitSolver>(*op_, settings_.damping.mass_coefficient(),
                                                 settings_.damping.stiffness_coefficient());
  const Eigen::Index n = op_->dofs();
  state_ = op_->rest_state();
  u_static_ = Eigen::VectorXd::Zero(n);
  f_ = Eigen::VectorXd::Zero(n);
  df_ = Eigen::VectorXd::Zero(n);
  force_static_.assign(footprints.size(), 0.0);
  force_last_.assign(footprints.size(), 0.0);
  peak_estimate_ = estimate_peak();
  report(mesh_seconds, seconds_since(start));
}

double FemSoil::estimate_peak() const {
  const ResidentMemory resident = resident_memory();
  if (resident.now == 0.0) return 0.0;  // (no /proc: nothing to start from)
  const auto dofs = static_cast<double>(op_->dofs());
  const auto nonzeros = static_cast<double>(op_->stiffness().nonzeros());
  double peak =
      std::max(resident.peak,
               resident.now + memory::statics_bytes(dofs, nonzeros, settings_.geometric_statics));
  if (implicit_)  // (the step factors K's combination as the statics' factor does)
    peak = std::max(peak,
                    resident.now + memory::kFactorBytesPerNonzero * memory::factor_nonzeros(dofs));
  return peak;
}

// mesh.refine on this process: the coarse mesh (gmsh's, or the cache's) cut into 8 per level,
// its nodes ordered again (docs/fem-soil.md §2). Refining keeps the coarse tetrahedra's shapes
// (gmsh's optimizer never sees the fine mesh), so the stable step falls below the rule's mesh's
// (measured 0.70x), much more where the coarse size near the track is wider than a footprint
// (0.32x: the footprints' edges flatten the coarse tetrahedra there): the log says so.
void FemSoil::refine_here(const std::vector<rumble::Footprint>& footprints) {
  using namespace rumble::fem;
  const std::size_t coarse_tets = mesh_.tets.size();
  const Eigen::Index coarse_nodes = mesh_.node_count();
  // (refine_uniformly's mesh, its nodes in Morton order, ties by their numbers: the order the
  // ranks reproduce, docs/fem-soil.md §8)
  NumberedRefinement fine = refine_numbered(mesh_, name_entities(mesh_), plan_.refine);
  // (statics.solver geometric: gmsh's mesh is the multigrid's coarse level, 1/8 of the fine
  // mesh's memory per level)
  if (settings_.geometric_statics) coarse_mesh_ = mesh_;
  renumber_nodes(fine.mesh, numbered_spatial_order(fine.mesh.nodes, fine.number,
                                                   fine.mesh.nodes.rowwise().minCoeff(),
                                                   fine.mesh.nodes.rowwise().maxCoeff()));
  mesh_ = std::move(fine.mesh);
  host_.info("fem: gmsh's mesh of " + format(static_cast<double>(coarse_nodes)) + " nodes, " +
             format(static_cast<double>(coarse_tets)) + " tetrahedra refined " +
             std::to_string(plan_.refine) +
             " times (mesh.refine): " + format(static_cast<double>(mesh_.dof_count())) + " DOFs");
  warn_if_coarse_near_track(footprints);
}

void FemSoil::warn_if_coarse_near_track(const std::vector<rumble::Footprint>& footprints) const {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const rumble::Footprint& f : footprints)
    narrowest = std::min({narrowest, f.width, f.length});
  const double coarse_near = plan_.coarse_scale() * plan_.h_near;
  if (coarse_near > narrowest)
    host_.warn(
        "fem: params/mesh/refine " + std::to_string(plan_.refine) + ": gmsh meshed at " +
        format(coarse_near) + " m near the track, wider than the narrowest footprint (" +
        format(narrowest) +
        " m): the tetrahedra along the footprints' edges are flattened and their children "
        "set the stable step (measured 0.32x of the rule's mesh's, against 0.70x where the "
        "coarse size stays below the footprints' width; docs/fem-soil.md section 2): lower "
        "mesh.refine where stepping, not meshing, is the cost (0: gmsh at the rule's sizes)");
}

rumble::fem::TetMesh FemSoil::cached_or_new_mesh() const {
  using namespace rumble::fem;
  const auto dir = mesh_cache_directory();
  if (!dir) {
    hint_fast_meshing();
    return generate_mesh(settings_, footprints_, plan_);
  }
  const auto path = *dir / mesh_cache_name(settings_, footprints_, plan_);
  if (auto cached = read_cached_mesh(path)) {
    host_.info("fem: mesh from the cache " + path.string());
    return std::move(*cached);
  }
  hint_fast_meshing();
  TetMesh mesh = generate_mesh(settings_, footprints_, plan_);
  if (!write_cached_mesh(path, mesh))
    host_.warn("fem: could not keep the mesh in " + path.string() +
               " (set RUMBLE_MESH_CACHE to a writable directory, or to off)");
  return mesh;
}

std::function<void()> FemSoil::throttled_stop_check() {
  return [this, last = std::chrono::steady_clock::now()]() mutable {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::milliseconds(100)) return;
    last = now;
    host_.check_stop();
  };
}

void FemSoil::report_ranks(double nodes, const char* source) const {
  const int ranks = host_.planned_ranks();  // (`rumble mesh --ranks N` on one process)
  if (ranks > 1 && !distributed_)
    host_.info(
        rumble::fem::describe(rumble::fem::plan_ranks(nodes, ranks, plan_choices()), source));
}

void FemSoil::report_split() const {
  const int ranks = host_.planned_ranks();
  if (ranks < 2 || distributed_) return;
  // MPI started by the host (a singleton), which finishes it once the plugins are gone (decision
  // 0012 §2): PETSc then leaves it alone. Started by PETSc, its MPI_Finalize at exit unloaded
  // this plugin under PetscFinalize's feet (a segfault after `rumble mesh --ranks 2` was done).
  host_.communicator();
  const rumble::fem::MeshSplit split = rumble::fem::split_mesh(mesh_, ranks);
  host_.info(rumble::fem::describe(
      split, rumble::fem::plan_split(static_cast<double>(split.nodes), ranks,
                                     static_cast<double>(split.ghosts),
                                     static_cast<double>(split.largest()), plan_choices())));
}

void FemSoil::hint_fast_meshing() const {
  constexpr double kLargeMeshDofs = 2e5;  // where Delaunay takes more than about 15 s
  // (gmsh meshes 8 times fewer tetrahedra per level of mesh.refine)
  const double gmsh_dofs = 3.0 * plan_.estimated_nodes / std::pow(8.0, plan_.refine);
  if (settings_.mesh.fast_algorithm || gmsh_dofs < kLargeMeshDofs) return;
  host_.info("fem: meshing about " + format(gmsh_dofs) +
             " DOFs with gmsh's delaunay (about 1e4 DOFs per second, one thread); "
             "params/mesh/algorithm \"hxt\" with mesh/threads 2 meshed 1e6 DOFs 15x faster "
             "(its mesh differs slightly from run to run; cached meshes are reused either way)");
}

void FemSoil::report(double mesh_seconds, double setup_seconds) const {
  using rumble::fem::BoundaryKind;
  double shortest_edge = 1e300;
  for (const auto& t : mesh_.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        shortest_edge = std::min(shortest_edge, (mesh_.node(t[a]) - mesh_.node(t[b])).norm());
  const double c_r = rayleigh_speed();
  std::ostringstream m;
  m << "fem: " << mesh_.node_count() << " nodes, " << mesh_.tets.size() << " tetrahedra, "
    << op_->dofs() << " DOFs, " << footprints_.size() << " footprints, " << op_->boundary().size()
    << " boundary nodes; shortest edge " << format(shortest_edge) << " m; meshed in "
    << format(mesh_seconds, 2) << " s, ready in " << format(setup_seconds, 2) << " s; "
    << format(op_->bytes() / 1048576.0) << " MiB ("
    << format(static_cast<double>(op_->bytes()) / op_->dofs(), 3) << " B per DOF; a run's peak "
    << "about " << format(peak_estimate_ / 1e9) << " GB, "
    << std::lround(peak_estimate_ / static_cast<double>(op_->dofs())) << " B per DOF); stable step "
    << format(op_->stable_step()) << " s (" << op_->eigen_iterations() << " Lanczos iterations), "
    << (implicit_ ? "implicit" : "explicit") << " step " << format(max_step()) << " s"
    << (op_->precision() == StepPrecision::kSingle ? " (K read in single precision)" : "");
  if (const auto& d = op_->maxwell_damping(); d.mechanisms() > 0)
    m << "; " << d.mechanisms() << " Maxwell mechanisms, ratio within "
      << format(100.0 * d.band_error(settings_.damping.ratio, settings_.damping.f_low,
                                     settings_.damping.f_high),
                2)
      << " % of " << settings_.damping.ratio << " over " << format(settings_.damping.f_low) << "-"
      << format(settings_.damping.f_high) << " Hz, static modulus "
      << format(settings_.damping.relaxed_modulus_factor(), 4) << " E, unrelaxed "
      << format(settings_.damping.relaxed_modulus_factor() * d.unrelaxed(), 4) << " E";
  if (plan_.radius > 0.0)  // (0: a user's mesh, whose sizes the soil did not choose)
    m << "; f_max resolved at " << settings_.mesh.elements_per_wavelength
      << " elements per Rayleigh wavelength:";
  for (double d : {2.5, 5.0, 10.0, 20.0, 40.0})
    if (d < plan_.radius)
      m << ' ' << format(plan_.resolved_frequency(d, c_r, settings_.mesh.elements_per_wavelength))
        << " Hz at " << d << " m;";
  if (const rumble::fem::PmlLayer* pml = op_->pml())
    m << " perfectly matched layer " << format(plan_.pml) << " m thick (elements up to "
      << format(plan_.h_pml) << " m): " << pml->tetrahedra() << " tetrahedra, damping up to "
      << format(pml->max_damping()) << " 1/s, which bounds the stable step to "
      << format(rumble::fem::PmlLayer::kStableDampingStep / pml->max_damping())
      << " s (a thicker layer or a higher boundary.pml.reflection lowers the damping and lifts "
         "the bound);";
  host_.info(m.str());
  const double epw = c_r / (settings_.mesh.f_max * plan_.h_near);
  if (plan_.h_near > 0.0 && epw < 8.0)
    host_.warn("fem: params/mesh/h_near " + format(plan_.h_near) + " m gives " + format(epw, 2) +
               " elements per Rayleigh wavelength at f_max " + format(settings_.mesh.f_max) +
               " Hz (c_R " + format(c_r) + " m/s); 8-10 are needed: lower h_near or f_max");
  if (settings_.boundary.kind == BoundaryKind::kDashpot)
    host_.warn(
        "fem: boundary.type dashpot has no static support: a change of the net "
        "footprint force makes the whole soil drift");
}

void FemSoil::enable_local_steps(rumble::fem::ExplicitSolver& step, double H, bool speak) {
  const double single = step.single_rate_step(), layer_limit = step.layer_step_limit();
  std::ostringstream m;
  m << "fem: local time stepping (integrator.local_steps " << settings_.local_steps << "): ";
  const auto start = std::chrono::steady_clock::now();
  const rumble::fem::LocalTimeStepping* lts =
      step.enable_local_steps(settings_.local_steps, H, settings_.courant) ? step.local_steps()
                                                                           : nullptr;
  const double seconds = seconds_since(start);
  if (lts == nullptr) {
    const double a1 = settings_.damping.stiffness_coefficient();
    if (layer_limit < 1.1 * single)
      m << "the matched layer's own limit on the step (" << format(layer_limit)
        << " s) is below 1.1 times one rate's (" << format(single)
        << " s), so there is nothing to gain; the soil steps on one rate (a thicker layer or a "
           "higher boundary.pml.reflection lifts that limit)";
    else if (rumble::fem::LocalTimeStepping::tau_for(single, a1) == 0.0)
      m << "the damping a1 K, taken half a step late, limits the step here (a1 = " << format(a1)
        << " s is " << format(a1 / single, 2) << " of the step " << format(single)
        << " s; local steps need below 0.4): set damping.model \"maxwell\" (frequency-flat "
           "mechanisms, nothing lags), raise damping.f_high or lower damping.ratio to lower "
           "a1, or set local_steps 1";
    else
      m << "no step longer than one rate's " << format(single)
        << " s that makes fewer sub-steps of the macro step " << format(H)
        << " s pays on this mesh (too many nodes would have to be fine, or the step needed is "
           "beyond local_steps times one rate's); the soil steps on one rate (set local_steps 1 "
           "to skip this search)";
    if (speak) host_.warn(m.str());
    return;
  }
  const rumble::fem::ExplicitSolver::LocalStepNodes nodes =
      step.local_step_nodes();  // (collective)
  m << nodes.fine << " fine nodes (" << format(100.0 * nodes.fine / nodes.nodes, 2) << " % of "
    << nodes.nodes << "; " << nodes.halo << " with their neighbours) take " << lts->substeps()
    << " steps per soil step; stable step " << format(step.stable_step()) << " s against "
    << format(single) << " s on one rate (x" << format(step.stable_step() / single, 3)
    << "): " << std::ceil(H / (settings_.courant * step.stable_step()) - 1e-9)
    << " sub-steps per macro step of " << format(H) << " s instead of "
    << std::ceil(H / (settings_.courant * single) - 1e-9) << " (chosen in " << format(seconds, 2)
    << " s)";
  if (speak) host_.info(m.str());
}

}  // namespace rumble::fem
