// The FEM soil under `mpirun -n N rumble run`, N > 1 (issue #33; docs/fem-soil.md §8, "On many
// ranks"; docs/decisions/0012-distributed-soil.md): the host makes each call on every rank with
// the same inputs. Rank 0 meshes the whole mesh and hands each rank its part; every rank then
// builds its share from its part alone (distributed/distributed_soil.hpp: its operator, boundary
// blocks, footprint weights, far field rows, receivers, and the stable step by Lanczos over the
// ranks), and the explicit steps run on the shares, their halos exchanged by PETSc. Rank 0 reads
// the footprints' motion and the receivers' samples, gathered in rank order, and keeps the whole
// mesh, not the whole operator; each rank writes its piece of a field snapshot
// (distributed/field_pieces.hpp). With mesh.refine rank 0 meshes and splits the coarse mesh only
// and each rank refines its part after the split (distributed/refined_partition.hpp).
//
// The static state: above the factor limit, or at any size with statics.solver named, GAMG on
// the ranks (distributed_statics.hpp) or the geometric multigrid on the ranks' refined parts
// (distributed/geometric_rank_statics.hpp: statics.solver geometric, or auto with mesh.refine);
// else, below the limit with auto, rank 0 factors the whole (small) operator as one process
// does, then frees it. What needs the
// whole operator (the receptance, the linear matrices) is refused on many ranks, and what cannot
// run there is refused when the soil is made, before any work: the refined mesh's export (it
// names its parameter and the fix), and so is a mesh whose estimate per rank outgrows a machine's
// memory.
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "distributed/field_pieces.hpp"
#include "distributed/node_memory.hpp"
#include "distributed/part_pml.hpp"
#include "distributed/rank_agreement.hpp"
#include "fem_soil.hpp"
#include "frequency/resolved_band.hpp"
#include "mesh/mesh_generator.hpp"
#include "mesh/mesh_memory.hpp"
#include "mesh/node_order.hpp"
#include "mesh/numbered_refinement.hpp"
#include "mesh/track_region.hpp"
#include "output/pvtu_writer.hpp"
#include "output/vtu_writer.hpp"

namespace rumble::fem {

namespace {

/// The fewest nodes a rank may take [-]: below, its halo is a large share of its nodes and the
/// exchange costs more than the rank saves (the medium soil's mesh at 1e4 nodes per rank: a
/// halo of some 15 % of them, docs/fem-soil.md "On many ranks").
constexpr double kFewestNodesPerRank = 1000.0;

/// Sub-steps in one macro step, at most (fem_stepping.cpp's bound).
constexpr double kMostSubStepsOnRanks = 1e9;

}  // namespace

void FemSoil::join_ranks() {
  int started = 0;
  MPI_Initialized(&started);  // (MPI runs under a launcher before any instance is made)
  if (!started) return;       // one process: never starts MPI here
  const std::optional<rumble::HostCommunicator> c = host_.communicator();
  if (!c || c->size < 2) return;
  refuse_on_many_ranks();
  distributed_ = std::make_unique<rumble::fem::DistributedSoil>(
      MPI_Comm_f2c(static_cast<MPI_Fint>(c->fortran_handle)));
  // Ctrl-C inside the ranks' static solves: rank 0 asks the host, every rank learns it at the
  // same CG iteration (statics/petsc_cg.hpp).
  if (distributed_->root()) distributed_->set_stop_check(throttled_stop_check());
  // tests/mpi's failures on purpose: "rank:seconds" (its steps from then on) or "rank:statics"
  // (its products in the static solve)
  if (const char* hook = std::getenv("RUMBLE_FEM_FAIL_RANK_AT")) {
    std::istringstream in(hook);
    char colon = 0;
    std::string at;
    in >> fail_rank_ >> colon >> at;
    if (at == "statics") {
      if (distributed_->rank() == fail_rank_)
        distributed_->fail_products_on_purpose(
            "fem: a product failed on purpose in the static solve on rank " +
            std::to_string(fail_rank_) + " (RUMBLE_FEM_FAIL_RANK_AT, a test's)");
      fail_rank_ = -1;
    } else {
      std::istringstream(at) >> fail_at_;
    }
  }
}

void FemSoil::refuse_on_many_ranks() const {
  const auto refuse = [](const std::string& key, const std::string& why) {
    throw std::invalid_argument("fem: params/" + key + ": " + why +
                                " (docs/fem-soil.md, \"On many ranks\")");
  };
  if (refine_on_ranks() > 0 && !settings_.mesh.export_file.empty())
    refuse("mesh/export",
           "with mesh.refine " + std::to_string(refine_on_ranks()) +
               " under mpirun no rank holds the refined mesh whole (each refines its part after "
               "the split); export it without mpirun (`rumble mesh`), or drop mesh.export under "
               "mpirun, got \"" +
               settings_.mesh.export_file + "\"");
}

void FemSoil::accept_layout_distributed(const std::vector<rumble::Footprint>& footprints) {
  rumble::fem::DistributedSoil& d = *distributed_;
  const auto start = std::chrono::steady_clock::now();
  footprints_ = footprints;
  const std::vector<rumble::fem::NodeShare> machines = rumble::fem::node_shares(d.comm());
  free_whole_on_root();  // (a previous layout's)
  whole_numbers_.clear();
  peak_estimate_ = 0.0;
  rumble::fem::on_root(d.comm(), [&] {
    const auto refuse_count = [&](double nodes, const char* what, const char* planned) {
      if (nodes >= kFewestNodesPerRank * d.ranks()) return;
      const int most = static_cast<int>(nodes / kFewestNodesPerRank);
      std::ostringstream m;
      m << "fem: " << what << " " << format(nodes) << " nodes" << planned << " cannot use "
        << d.ranks() << " ranks: each would hold under " << kFewestNodesPerRank
        << " nodes, where the halo exchange costs more than a rank saves; "
        << (most < 2 ? std::string("run it without mpirun")
                     : "run on at most " + std::to_string(most) + " ranks (mpirun -n " +
                           std::to_string(most) + ")")
        << ", or refine the mesh (mesh.f_max, mesh.h_near)";
      throw std::invalid_argument(m.str());
    };
    // Each machine's memory for its ranks, against the estimate per rank (distributed/
    // rank_plan.hpp): before meshing from the plan, again from the mesh.
    const auto check_memory = [&](double nodes, const char* source) {
      const rumble::fem::RankPlan plan = rumble::fem::plan_ranks(nodes, d.ranks(), plan_choices());
      host_.info(rumble::fem::describe(plan, source));
      rumble::fem::check_node_memory(plan, machines, settings_.mesh.f_max);
    };
    if (settings_.mesh.file.empty()) {  // (before meshing: the plan's estimate)
      const double planned = rumble::fem::plan_mesh(settings_, footprints).estimated_nodes;
      refuse_count(planned, "a mesh of about", " (planned)");
      check_memory(planned, "the plan's estimate");
    }
    mesh_here(footprints);  // (with mesh.refine on the ranks: gmsh's coarse mesh)
    const double nodes =
        refine_on_ranks() > 0 ? refined_node_count() : static_cast<double>(mesh_.node_count());
    refuse_count(nodes, "the mesh's", "");
    check_memory(nodes, "the mesh");
  });
  // The matched layer's box: rank 0's plan, the same on every rank.
  std::optional<rumble::fem::PmlProfile> pml;
  if (settings_.boundary.kind == rumble::fem::BoundaryKind::kPml)
    pml = rumble::fem::from_root(d.root() ? pml_profile() : rumble::fem::PmlProfile{}, d.comm());
  // (a rank failing alone inside the split, the refinement or the build stops every rank with
  // its message rather than leave them waiting: distributed/rank_agreement.hpp)
  rumble::fem::collective(d.comm(), [&] {
    d.lay_out(d.root() ? &mesh_ : nullptr, settings_, footprints, host_.threads(),
              refine_on_ranks(), pml ? &*pml : nullptr);
  });
  // (statics.solver gamg, geometric or aggregation named: on the ranks at any size, as asked)
  statics_on_root_ =
      !settings_.statics_named && d.whole_dofs() <= rumble::fem::StaticSolver::kFactorLimit;
  if (statics_on_root_)  // (the whole operator for the factor: small below its limit)
    rumble::fem::on_root(d.comm(), [&] {
      if (d.refined() > 0) refine_whole_on_root();
      build_here(footprints, 0.0, start);
    });
  peak_estimate_ = std::max(peak_estimate_, d.peak_estimate());
  force_static_.assign(footprints.size(), 0.0);
  force_last_.assign(footprints.size(), 0.0);
  const std::string summary = d.summary();
  if (d.root()) host_.info(summary);
}

double FemSoil::refined_node_count() const {
  return static_cast<double>(
      rumble::fem::refined_counts(rumble::fem::name_entities(mesh_), refine_on_ranks()).nodes);
}

void FemSoil::refine_whole_on_root() {
  using namespace rumble::fem;
  NumberedRefinement fine = refine_numbered(mesh_, name_entities(mesh_), refine_on_ranks());
  const std::vector<std::int32_t> order =
      numbered_spatial_order(fine.mesh.nodes, fine.number, fine.mesh.nodes.rowwise().minCoeff(),
                             fine.mesh.nodes.rowwise().maxCoeff());
  renumber_nodes(fine.mesh, order);  // (refine_here's mesh, node for node)
  whole_numbers_.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    whole_numbers_[k] = static_cast<std::int32_t>(fine.number[order[k]]);
  mesh_ = std::move(fine.mesh);
  host_.info("fem: below the factor limit rank 0 refines the whole coarse mesh too (" +
             format(static_cast<double>(mesh_.dof_count())) +
             " DOFs), for the static state's factor as one process solves it");
}

void FemSoil::free_whole_on_root() {
  op_.reset();
  statics_.reset();
  far_field_.reset();
  implicit_.reset();
  weights_ = {};
  state_ = {};
  u_static_ = f_ = df_ = Eigen::VectorXd();
}

void FemSoil::refuse_whole_operator(const std::string& what) const {
  throw std::invalid_argument(
      "fem: " + what + " needs the soil's whole operator, which no rank holds under mpirun -n " +
      std::to_string(distributed_->ranks()) +
      " (each holds its part); run it without mpirun, on one process (docs/fem-soil.md §8)");
}

void FemSoil::initialize_distributed(double t0, const double* static_force, double* static_u) {
  rumble::fem::DistributedSoil& d = *distributed_;
  force_static_.assign(static_force, static_force + footprints_.size());
  force_last_ = force_static_;
  static_average_.assign(footprints_.size(), 0.0);
  const double distance = d.set_far_field(settings_, footprints_);
  far_lag_.tau =  // (as one process's far_field(), from the ranks' boundary nodes)
      distance / rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space).shear;
  if (!statics_on_root_) {
    solve_static_on_ranks(static_force, static_u);
  } else {  // rank 0 factors the whole mesh as one process does, the ranks take their share
    rumble::fem::on_root(d.comm(), [&] {
      if (!op_)  // (freed by statics_done: built again from the whole mesh)
        build_here(footprints_, 0.0, std::chrono::steady_clock::now());
      initialize_here(t0, static_force, static_u);
      for (std::size_t j = 0; j < footprints_.size(); ++j)
        static_average_[j] = average(j, u_static_);
    });
    Eigen::VectorXd numbered;  // (rank 0's whole refined mesh: in the ranks' numbers)
    if (d.root() && !whole_numbers_.empty()) {
      numbered.resize(u_static_.size());
      for (std::size_t k = 0; k < whole_numbers_.size(); ++k)
        numbered.segment<3>(3 * static_cast<Eigen::Index>(whole_numbers_[k])) =
            u_static_.segment<3>(3 * static_cast<Eigen::Index>(k));
    }
    d.set_static(d.root() ? (whole_numbers_.empty() ? &u_static_ : &numbered) : nullptr);
  }
  ExplicitState& s = d.state();
  s.w.setZero();
  s.v.setZero();
  s.a.setZero();
  s.pml.setZero();
  s.maxwell.setZero();
  far_lag_.lagged.assign(footprints_.size(), 0.0);
  far_change_.assign(footprints_.size(), 0.0);
  far_step_.assign(footprints_.size(), 0.0);
}

void FemSoil::solve_static_on_ranks(const double* static_force, double* static_u) {
  rumble::fem::DistributedSoil& d = *distributed_;
  rumble::fem::on_root(d.comm(), [&] { export_if_due(); });
  const auto start = std::chrono::steady_clock::now();
  bool first = false;  // (PETSc's set-up and CG: as the lay-out above)
  rumble::fem::collective(d.comm(),
                          [&] { first = d.solve_static(static_force, static_average_.data()); });
  if (!d.root()) return;
  for (std::size_t j = 0; j < footprints_.size(); ++j) static_u[j] = static_average_[j];
  const rumble::fem::RankStatics& statics = *d.statics();
  const std::string solved = "in " + format(seconds_since(start), 2) + " s, " +
                             std::to_string(statics.last_iterations()) + " CG iterations";
  if (first)
    host_.info("fem: static solves by PETSc's " + std::string(statics.method()) + " on " +
               std::to_string(d.ranks()) + " ranks (to " + format(statics.tolerance()) +
               " of the load): " + std::to_string(statics.levels()) + " levels" +
               statics.levels_detail() + ", set up in " + format(statics.setup_seconds(), 2) +
               " s; the first solve, set-up included, " + solved);
  else
    host_.log(RUMBLE_LOG_DEBUG,
              "fem: static solve (" + std::string(statics.method()) + " on the ranks) " + solved);
}

void FemSoil::distributed_forces(const rumble::Waveform& force, double tau, Eigen::VectorXd& out,
                                 const double* reference) const {
  const rumble::fem::FootprintWeights& weights = distributed_->weights();
  for (const auto& footprint : weights)
    for (const rumble::fem::NodalWeight& w : footprint) out[3 * w.node + 2] = 0.0;
  for (std::size_t j = 0; j < weights.size(); ++j) {
    const double F = force.at(j, tau) - reference[j];
    for (const rumble::fem::NodalWeight& w : weights[j]) out[3 * w.node + 2] += w.weight * F;
  }
}

void FemSoil::follow_far_field_distributed(const rumble::Waveform& force, double H) {
  for (std::size_t j = 0; j < footprints_.size(); ++j) {
    far_change_[j] = force.at(j, 0.5) - force_static_[j];
    far_step_[j] = far_lag_.lagged[j];  // (the change the boundary held before)
  }
  far_lag_.advance(far_change_, H);
  distributed_->follow_far_field(far_step_.data(), far_lag_.lagged.data());
}

void FemSoil::advance_distributed(double t, double H, const rumble::Waveform& force) {
  rumble::fem::DistributedSoil& d = *distributed_;
  rumble::fem::ExplicitSolver& step = d.step();
  rumble::fem::ImplicitSolver* implicit = d.implicit();
  const char* scheme = implicit ? "implicit" : "explicit";
  tuner_.grant(host_.threads());
  step.set_threads(tuner_.threads());
  if (settings_.local_steps > 1 && !implicit && !local_steps_chosen_) {
    enable_local_steps(step, H, d.root());  // (collective: the same choice on every rank)
    local_steps_chosen_ = true;
  }
  // (every rank has the same stable step, from Lanczos over the ranks, or the same implicit
  // step from the settings: the same sub-steps)
  const double longest =
      implicit ? settings_.implicit_step : settings_.courant * step.stable_step();
  const double count = std::ceil(H / longest - 1e-9);
  if (!(count <= kMostSubStepsOnRanks))
    throw std::invalid_argument("fem: a macro step of " + format(H) + " s is " + format(count) +
                                " " + scheme + " sub-steps, more than " +
                                format(kMostSubStepsOnRanks) + "; lower /time/macro_step");
  const int sub_steps = std::max(1, static_cast<int>(count));
  const double dt = H / sub_steps;
  if (H != reported_macro_step_ && d.root())
    host_.log(reported_macro_step_ < 0.0 ? RUMBLE_LOG_INFO : RUMBLE_LOG_DEBUG,
              "fem: " + std::to_string(sub_steps) + " " + scheme + " sub-step(s) of " + format(dt) +
                  " s per macro step of " + format(H) + " s on each of " +
                  std::to_string(d.ranks()) + " ranks, " + std::to_string(step.threads()) +
                  " thread(s) on rank 0" +
                  (implicit ? " (each solved by MUMPS's Cholesky factor over the ranks)" : ""));
  reported_macro_step_ = H;
  distributed_forces(force, 0.0, d.force_jump(), force_last_.data());
  if (d.has_far_field() && settings_.boundary.far_field_follows)
    follow_far_field_distributed(force, H);
  step.force_jump(d.state(), d.force_jump());
  auto last_check = std::chrono::steady_clock::now();
  for (int k = 1; k <= sub_steps; ++k) {
    const double tau = static_cast<double>(k) / sub_steps;
    distributed_forces(force, tau, d.force(), force_static_.data());
    const auto start = std::chrono::steady_clock::now();
    if (implicit) {  // (K's product and the factor's solve: collective, a failure every rank's)
      rumble::fem::collective(d.comm(), [&] { implicit->step(d.state(), d.force(), dt); });
    } else {
      step.step(d.state(), d.force(), dt);
      tuner_.record(seconds_since(start));
      if (tuner_.threads() != step.threads()) step.set_threads(tuner_.threads());
    }
    std::exception_ptr failure;  // (agreed below, as every rank's of this sub-step)
    try {
      record_probes(t + tau * H);
    } catch (...) {
      failure = std::current_exception();
    }
    // Every rank learns at the same sub-step whether rank 0 is asked to stop (Ctrl-C, checked
    // every 0.1 s) or a rank failed: each stops there, none waits in the next exchange.
    bool stop = false;
    if (d.root() &&
        std::chrono::steady_clock::now() - last_check > std::chrono::milliseconds(100)) {
      stop = host_.stop_requested(tau);
      last_check = std::chrono::steady_clock::now();
    }
    if (!failure && d.rank() == fail_rank_ && t + tau * H >= fail_at_)
      failure = std::make_exception_ptr(std::runtime_error(
          "fem: failed on purpose at t = " + format(t + tau * H, 6) + " s on rank " +
          std::to_string(d.rank()) + " (RUMBLE_FEM_FAIL_RANK_AT, a test's)"));
    rumble::fem::agree(d.comm(), failure, stop);
  }
  for (std::size_t j = 0; j < footprints_.size(); ++j) force_last_[j] = force.at(j, 1.0);
  std::vector<double> w(footprints_.size()), v(footprints_.size());
  d.footprint_motion(w.data(), v.data());
  if (!d.root()) return;  // (rank 0 checks the sums: the last collective call is behind)
  for (std::size_t j = 0; j < footprints_.size(); ++j)
    if (!std::isfinite(w[j]) || !std::isfinite(v[j]))
      throw std::runtime_error(
          "fem: the motion of footprint " + std::to_string(j) +
          " is not finite at t = " + format(t + H) + " s: " +
          (implicit
               ? std::string("the forces are not finite")
               : "the explicit step " + format(dt) + " s is unstable (lower params/courant, now " +
                     format(settings_.courant) + ") or the forces are not finite"));
}

void FemSoil::motion_distributed(double* u, double* v) const {
  std::vector<double> w(footprints_.size());
  distributed_->footprint_motion(w.data(), v);
  if (!distributed_->root()) return;
  for (std::size_t j = 0; j < footprints_.size(); ++j) u[j] = static_average_[j] + w[j];
}

void FemSoil::set_probes_distributed(const std::vector<rumble::Probe>& probes,
                                     double sample_interval) {
  rumble::fem::DistributedSoil& d = *distributed_;
  // The resolution along each path: the largest tetrahedron on it over the ranks' parts, the
  // lowest frequency of those found (0: none on a rank's part), the whole mesh's exactly.
  std::vector<Eigen::Vector3d> points;
  for (const rumble::Probe& p : probes) points.emplace_back(p.x, p.y, p.depth);
  std::vector<double> mine = rumble::fem::path_resolved_frequency(
      d.partition().mesh, rumble::fem::TrackRegion::of(footprints_), points, rayleigh_speed(),
      settings_.mesh.elements_per_wavelength);
  for (double& f : mine)
    if (f == 0.0) f = std::numeric_limits<double>::infinity();
  probe_resolution_.assign(probes.size(), 0.0);
  MPI_Reduce(mine.data(), probe_resolution_.data(), static_cast<int>(mine.size()), MPI_DOUBLE,
             MPI_MIN, 0, d.comm());
  for (double& f : probe_resolution_)
    if (std::isinf(f)) f = 0.0;
  d.set_probes(probes);  // (each receiver placed and sampled by the rank whose part holds it)
  probes_.assign(probes.size(), {});
  row_.assign(probes.size() * RUMBLE_PROBE_VALUES, 0.0);
  sample_interval_ = sample_interval;
  next_sample_ = -1.0;
}

void FemSoil::write_fields_distributed(double t, const std::string& path) {
  rumble::fem::DistributedSoil& d = *distributed_;
  if (rumble::fem::is_parallel_snapshot(path)) {
    rumble::fem::on_root(d.comm(), [&] { export_if_due(); });
    return rumble::fem::write_field_pieces(d, t, path);
  }
  if (d.refined() > 0)  // (every rank alike: before any collective call)
    throw std::invalid_argument(
        "fem: a .vtu of the whole mesh (" + path + ") under mpirun with mesh.refine " +
        std::to_string(d.refined()) +
        ": no rank holds the refined mesh whole (each refined its part after the split); run "
        "`rumble mesh` without mpirun, or set mesh.refine 0 under mpirun (a run's snapshots "
        "under mpirun, .pvtu pieces written by each rank, need no whole mesh; docs/fem-soil.md "
        "§8)");
  // A .vtu asked of many ranks (`rumble mesh` under mpirun): gathered on rank 0, as one file.
  const Eigen::Index n = d.root() ? mesh_.dof_count() : 0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), w = u, v = u;
  d.gather(d.static_state(), d.root() ? &u : nullptr);
  d.gather(d.state().w, d.root() ? &w : nullptr);
  d.gather(d.state().v, d.root() ? &v : nullptr);
  if (!d.root()) return;
  export_if_due();
  rumble::fem::write_vtu(path, t, mesh_, u + w, v);
}

}  // namespace rumble::fem
