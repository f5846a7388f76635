// fem: the soil as a 3D finite-element half-space (docs/soils.md, "FEM soil"). Meshed with gmsh
// when the track announces its footprints; linear tetrahedra, lumped mass, Rayleigh damping,
// Lysmer-Kuhlemeyer dashpots with springs on the truncation surface; the static state from one
// sparse Cholesky solve, the motion about it by explicit central differences sub-cycled inside
// each macro step. The footprint forces act as uniform pressures on the footprints; the track
// sees their area-averaged vertical motion (footprint_loads.hpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <rumble/params_file.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/pml.hpp"
#include "boundary/static_far_field.hpp"
#include "fem_settings.hpp"
#include "frequency/impulse_receptance.hpp"
#include "frequency/receptance.hpp"
#include "frequency/receptance_cache.hpp"
#include "frequency/resolved_band.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/mesh_cache.hpp"
#include "mesh/mesh_generator.hpp"
#include "operator/elasticity.hpp"
#include "operator/footprint_loads.hpp"
#include "operator/linear_matrices.hpp"
#include "output/probe_locator.hpp"
#include "output/vtu_writer.hpp"
#include "results_file.hpp"
#include "statics/static_solver.hpp"
#include "time/explicit_solver.hpp"
#include "time/implicit_solver.hpp"
#include "time/thread_tuner.hpp"
#include "wave_speeds.hpp"

namespace {

using rumble::fem::ExplicitState;
using rumble::fem::StepPrecision;

/// Sub-steps in one macro step, at most (as the lumped soils): beyond, a macro step is a mistake.
constexpr double kMaxSubSteps = 1e9;

std::string format(double x, int digits = 3) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

class FemSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "fem";
  static constexpr const char* kSummary =
      "3D finite-element half-space meshed with gmsh (linear tetrahedra, Lysmer-Kuhlemeyer "
      "viscous-spring boundary, explicit sub-cycled steps, receivers at any depth, VTU fields)";
  /// Its matrices make it a soil for the monolithic reference (small meshes: the engine holds
  /// them banded) and for `rumble stability`.
  static constexpr std::uint64_t kCapabilities = rumble::kCapThreads | rumble::kCapLinearMatrices;
  static const char* params_schema() { return rumble::fem::settings_schema(); }

  FemSoil(const std::string& params_json, const rumble::Host& host)
      : settings_(rumble::fem::read_settings(params_json)),
        params_(nlohmann::json::parse(params_json).dump()),
        host_(host) {
    // A mesh file is found (and sized) at once, so that validation names it at params.
    if (!settings_.mesh.file.empty()) {
      const double limit = settings_.mesh.max_file_bytes();
      mesh_file_ =
          rumble::checked_params_file(
              "fem: params/mesh/file", settings_.mesh.file,
              nlohmann::json(settings_.mesh.file).dump(), host_.scenario_dir(),
              {.noun = "a mesh file",
               .file_noun = "a gmsh mesh file (.msh)",
               .max_bytes = static_cast<std::uintmax_t>(limit),
               .too_large_fix = "is this the right file? (the limit is 256 bytes per "
                                "mesh.max_dofs, now " +
                                format(settings_.mesh.max_dofs) + "; raise it for a larger mesh)"})
              .lexically_normal()
              .string();
    }
  }

  void accept_layout(const std::vector<rumble::Footprint>& footprints) override {
    using namespace rumble::fem;
    const auto start = std::chrono::steady_clock::now();
    receptance_.reset();  // it refers to the operators of the previous layout
    impulse_.reset();
    receptance_key_.reset();
    footprints_ = footprints;
    if (settings_.mesh.file.empty()) {
      plan_ = plan_mesh(settings_, footprints);
      host_.info("fem: a mesh of about " + format(3.0 * plan_.estimated_nodes) + " DOFs (h_near " +
                 format(plan_.h_near) + " m, h_max " + format(plan_.h_max) + " m, radius " +
                 format(plan_.radius) + " m)");
      mesh_ = cached_or_new_mesh();
      export_due_ = !settings_.mesh.export_file.empty();
      export_if_due();
    } else {
      MeshFile file = load_mesh_file(settings_, mesh_file_);
      check_mesh_footprints(file, footprints);
      mesh_ = std::move(file.mesh);
      plan_ = {.region = TrackRegion::of(footprints)};  // sizes unknown: radius 0
      host_.info("fem: mesh read from " + mesh_file_);
    }
    const double mesh_seconds = seconds_since(start);
    weights_ = footprint_weights(mesh_, footprints);
    std::vector<BoundaryNode> boundary = absorbing_boundary(mesh_, settings_, footprints);
    std::vector<char> fixed(mesh_.node_count(), 0);
    // Behind a matched layer the surface is fixed: with the viscous-spring blocks or dashpots
    // there the discrete layer grew at every step tried (docs/fem-soil.md section 3.1).
    if (settings_.boundary.kind == BoundaryKind::kFixed ||
        settings_.boundary.kind == BoundaryKind::kPml)
      for (const BoundaryNode& b : boundary) fixed[b.node] = 1;
    op_.emplace(assemble_stiffness(mesh_, settings_), lumped_mass(mesh_, settings_),
                std::move(boundary), settings_.boundary.springs(), std::move(fixed),
                settings_.damping.mass_coefficient(), settings_.damping.stiffness_coefficient(),
                host_.threads(),
                settings_.single_precision_step ? StepPrecision::kSingle : StepPrecision::kDouble);
    op_->set_loaded_nodes(loaded_nodes(weights_));  // (the footprints' forces act there only)
    // Ctrl-C inside the static solves and the local steps' choice, checked every 0.1 s at most.
    op_->set_stop_check([this, last = std::chrono::steady_clock::now()]() mutable {
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(100)) return;
      last = now;
      host_.check_stop();
    });
    if (settings_.damping.maxwell) op_->set_maxwell_damping(settings_.damping.maxwell_mechanisms());
    if (settings_.boundary.kind == BoundaryKind::kPml)
      op_->set_pml(PmlLayer(mesh_, settings_, pml_profile()));
    local_steps_chosen_ = false;  // (at the first macro step, whose length they are fitted to)
    statics_ = std::make_unique<StaticSolver>(op_->soil(), mesh_.nodes);
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
    report(mesh_seconds, seconds_since(start));
  }

  void initialize(double /*t0*/, const double* static_force, double* static_u) override {
    require_layout("initialize");
    export_if_due();  // a run's soil was laid out by its validation, before it had a directory
    op_->set_threads(host_.threads());  // the statics' products and multigrid set-up use them
    force_static_.assign(static_force, static_force + footprints_.size());
    force_last_ = force_static_;
    spread(force_static_.data(), f_);
    add_static_far_field(force_static_.data(), f_);
    // No static load (a check, or a soil driven by forces alone): no factor needed.
    const auto start = std::chrono::steady_clock::now();
    const bool first_multigrid = statics_->multigrid() == nullptr;
    u_static_ = f_.isZero(0.0) ? Eigen::VectorXd::Zero(f_.size()) : statics_->solve(f_);
    if (first_multigrid && statics_->multigrid() != nullptr)
      host_.info("fem: multigrid for the static solves: " +
                 std::to_string(statics_->multigrid()->levels()) + " levels, set up in " +
                 format(statics_->multigrid_setup_seconds(), 2) + " s");
    if (!statics_->factored() && statics_->last_cg_iterations() > 0)
      host_.log(RUMBLE_LOG_DEBUG, "fem: static solve in " + format(seconds_since(start), 2) +
                                      " s, " + std::to_string(statics_->last_cg_iterations()) +
                                      " CG iterations");
    for (Eigen::Index k = 0; k < f_.size(); ++k) f_[k] = 0.0;
    state_.w.setZero();
    state_.v.setZero();
    state_.a.setZero();
    state_.pml.setZero();                             // the layer at rest
    state_.maxwell.setZero();                         // the mechanisms relaxed
    far_lag_.lagged.assign(footprints_.size(), 0.0);  // the boundary holds the static traction
    for (std::size_t j = 0; j < footprints_.size(); ++j) static_u[j] = average(j, u_static_);
  }

  void finalize() override {
    // Which team sizes the explicit steps ran on, when the host granted more than one thread:
    // on a busy machine, one thread most of the time (time/thread_tuner.hpp).
    if (tuner_.sizes().size() > 1 && !tuner_.account().empty())
      host_.log(RUMBLE_LOG_INFO, "fem: explicit steps on " + tuner_.account() +
                                     ", each size taken as the machine let it step fastest");
  }

  void advance(double t, double H, const rumble::Waveform& force) override {
    require_layout("advance");
    // Granted with the run context, after the layout; the explicit step uses what the tuner finds
    // fastest on this machine now (time/thread_tuner.hpp).
    tuner_.grant(host_.threads());
    op_->set_threads(implicit_ ? host_.threads() : tuner_.threads());
    if (settings_.local_steps > 1 && !implicit_ && !local_steps_chosen_) {
      enable_local_steps(H);
      local_steps_chosen_ = true;
    }
    // Counted in floating point first: a macro step far beyond the soil's step must not overflow
    // the count (any H is cut into equal sub-steps; only their number is bounded).
    const double count = std::ceil(H / max_step() - 1e-9);
    if (!(count <= kMaxSubSteps)) {
      std::ostringstream m;
      m << "fem: a macro step of " << H << " s in " << (implicit_ ? "implicit" : "explicit")
        << " sub-steps of at most " << format(max_step()) << " s is " << count
        << " sub-steps, more than " << kMaxSubSteps << "; lower /time/macro_step";
      throw std::invalid_argument(m.str());
    }
    const int sub_steps = std::max(1, static_cast<int>(count));
    const double dt = H / sub_steps;
    if (H != reported_macro_step_) {  // once at info level, later changes (adaptive H) at debug
      host_.log(reported_macro_step_ < 0.0 ? RUMBLE_LOG_INFO : RUMBLE_LOG_DEBUG,
                "fem: " + std::to_string(sub_steps) + " " + (implicit_ ? "implicit" : "explicit") +
                    " sub-step(s) of " + format(dt) + " s per macro step of " + format(H) + " s, " +
                    std::to_string(op_->threads()) + " thread(s)");
      reported_macro_step_ = H;
    }
    // The force may jump at the step's start (a held or extrapolated waveform): the acceleration
    // at t follows it.
    footprint_forces(force, 0.0, df_, force_last_.data());
    if (far_field_ && settings_.boundary.far_field_follows) follow_far_field(force, H);
    op_->force_jump(state_, df_);
    auto last_check = std::chrono::steady_clock::now();
    for (int k = 1; k <= sub_steps; ++k) {
      const double tau = static_cast<double>(k) / sub_steps;
      footprint_forces(force, tau, f_, force_static_.data());
      const auto start = std::chrono::steady_clock::now();
      if (implicit_) {
        implicit_->step(state_, f_, dt);
      } else {
        op_->step(state_, f_, dt);
        tune_threads(std::chrono::steady_clock::now() - start);
      }
      record_probes(t + tau * H);
      const auto now = std::chrono::steady_clock::now();
      if (now - last_check > std::chrono::milliseconds(100)) {
        host_.check_stop(tau);
        last_check = now;
      }
    }
    for (std::size_t j = 0; j < footprints_.size(); ++j) force_last_[j] = force.at(j, 1.0);
    for (std::size_t j = 0; j < footprints_.size(); ++j)
      if (!std::isfinite(average(j, state_.w)) || !std::isfinite(average(j, state_.v))) {
        std::ostringstream m;
        m << "fem: the motion of footprint " << j << " is not finite at t = " << t + H << " s: "
          << (implicit_ ? "the forces are not finite"
                        : "the explicit step " + format(dt) +
                              " s is unstable (lower params/courant, now " +
                              format(settings_.courant) + ") or the forces are not finite");
        throw std::runtime_error(m.str());
      }
  }

  void motion(double* u, double* v) const override {
    for (std::size_t j = 0; j < footprints_.size(); ++j) {
      u[j] = average(j, u_static_) + average(j, state_.w);
      v[j] = average(j, state_.v);
    }
  }

  void set_probes(const std::vector<rumble::Probe>& probes, double sample_interval) override {
    require_layout("set_probes");
    probes_.clear();
    for (const rumble::Probe& p : probes) {
      if (op_->pml() && !pml_profile().inside_physical_box({p.x, p.y, p.depth})) {
        std::ostringstream m;
        m << "fem: probe \"" << p.name << "\" at (" << p.x << ", " << p.y << ", " << p.depth
          << ") m lies in the perfectly matched layer, whose motion is not physical; move it into "
             "the box (within params/mesh/radius = "
          << plan_.radius << " m of the footprints, depth at most " << plan_.radius
          << " m) or raise mesh.radius";
        throw std::invalid_argument(m.str());
      }
      probes_.push_back(rumble::fem::locate_probe(mesh_, p.x, p.y, p.depth, p.name));
    }
    std::vector<Eigen::Vector3d> points;
    for (const rumble::Probe& p : probes) points.emplace_back(p.x, p.y, p.depth);
    probe_resolution_ = rumble::fem::path_resolved_frequency(
        mesh_, rumble::fem::TrackRegion::of(footprints_), points, rayleigh_speed(),
        settings_.mesh.elements_per_wavelength);
    row_.assign(probes.size() * RUMBLE_PROBE_VALUES, 0.0);
    sample_interval_ = sample_interval;
    next_sample_ = -1.0;
  }

  std::vector<double> probe_resolution(std::string& rule) const override {
    rule = "f = c_R / (n h): n = " + format(settings_.mesh.elements_per_wavelength) +
           " linear elements per Rayleigh wavelength (mesh.elements_per_wavelength), c_R = " +
           format(rayleigh_speed()) +
           " m/s (the slowest layer's), h the mean edge of the largest tetrahedron on the "
           "straight path from the nearest footprint to the receiver (docs/fem-soil.md 2.2)";
    return probe_resolution_;
  }

  void write_fields(double t, const std::string& path) override {
    require_layout("write_fields");
    export_if_due();  // `rumble mesh` gives a directory, then asks for the fields only
    rumble::fem::write_vtu(path, t, mesh_, u_static_ + state_.w, state_.v);
  }

  bool frequency_response(double f_hz, std::complex<double>* receptance) override {
    require_layout("frequency_response");
    using namespace rumble::fem;
    const auto dir = mesh_cache_directory();
    std::filesystem::path cached;
    if (dir) {
      if (!receptance_key_) receptance_key_ = receptance_soil_key(mesh_, params_, weights_);
      cached = *dir / receptance_cache_name(*receptance_key_, f_hz);
      if (read_cached_receptance(cached, f_hz, footprints_.size(), receptance)) {
        host_.log(RUMBLE_LOG_DEBUG,
                  "fem: receptance at " + format(f_hz) + " Hz from the cache " + cached.string());
        return true;
      }
    }
    if (settings_.receptance.impulse) {
      op_->set_threads(host_.threads());
      if (!impulse_) impulse_ = impulse_responses();
      impulse_->at(f_hz, receptance);
    } else {
      if (!receptance_) {
        receptance_ =
            std::make_unique<Receptance>(*op_, weights_, settings_.damping.mass_coefficient(),
                                         settings_.damping.stiffness_coefficient());
        if (settings_.boundary.far_field_follows)
          receptance_->set_far_field(far_field(), &far_lag_);
      }
      receptance_->at(f_hz, receptance);
    }
    if (dir && !write_cached_receptance(cached, f_hz, footprints_.size(), receptance) &&
        !receptance_cache_warned_) {
      host_.warn("fem: could not keep the receptance in " + cached.string() +
                 " (set RUMBLE_MESH_CACHE to a writable directory, or to off)");
      receptance_cache_warned_ = true;
    }
    return true;
  }

  void linear_matrix(rumble_matrix which, rumble::CscMatrix& out) override {
    require_layout("linear_matrix");
    refuse_with_pml("its matrices (the monolithic coupler, rumble stability)");
    if (settings_.damping.maxwell)
      throw std::invalid_argument(
          "fem: params/damping/model: the Maxwell mechanisms' memory has no place in M, C and K "
          "(the monolithic coupler, rumble stability); use damping.model \"rayleigh\" for them, "
          "got \"maxwell\"");
    rumble::fem::linear_matrix(op_->soil(), weights_, settings_.damping.mass_coefficient(),
                               settings_.damping.stiffness_coefficient(), which, out);
    if (which == RUMBLE_MATRIX_STIFFNESS && settings_.boundary.far_field_follows &&
        rumble::fem::static_far_field_applies(settings_))
      host_.info(
          "fem: the linear matrices hold the far field's traction at the statics' (a load "
          "change settles through the springs alone); the soil's own steps follow the forces: "
          "set params/boundary/far_field \"static\" for the same motion both ways "
          "(docs/fem-soil.md section 3.2)");
  }

  void wave_speeds(double& c_s_min, double& c_r_min) const override {
    const auto s = rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space);
    c_s_min = s.shear;
    c_r_min = s.rayleigh;
  }

  /// [m/s] the slowest layer's Rayleigh speed: the mesh's sizes follow its wavelength.
  double rayleigh_speed() const {
    return rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space).rayleigh;
  }

  void checkpoint_save(std::uint32_t slot) override {
    require_layout("checkpoint_save");
    Checkpoint& c = checkpoints_.at(slot);
    c.state = state_;
    c.force_last = force_last_;
    c.far_lagged = far_lag_.lagged;
    c.next_sample = next_sample_;
    c.valid = true;
  }
  void checkpoint_restore(std::uint32_t slot) override {
    const Checkpoint& c = checkpoints_.at(slot);
    if (!c.valid)
      throw std::logic_error("fem: checkpoint slot " + std::to_string(slot) + " is empty");
    state_ = c.state;
    force_last_ = c.force_last;
    far_lag_.lagged = c.far_lagged;
    next_sample_ = c.next_sample;
  }
  void checkpoint_free(std::uint32_t slot) override { checkpoints_.at(slot) = {}; }

 private:
  struct Checkpoint {
    ExplicitState state;
    std::vector<double> force_last;
    std::vector<double> far_lagged;  // FarFieldLag::lagged
    double next_sample = -1.0;
    bool valid = false;
  };

  static double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void require_layout(const char* call) const {
    if (!op_) throw std::logic_error(std::string("fem: ") + call + "() before accept_layout()");
  }

  /// One explicit run per footprint (impulse_receptance.hpp), with progress and Ctrl-C.
  std::unique_ptr<rumble::fem::ImpulseReceptance> impulse_responses() {
    const rumble::fem::StaticFarField* far =
        settings_.boundary.far_field_follows ? far_field() : nullptr;
    const double dt = settings_.courant * op_->stable_step();
    const double duration = settings_.receptance.duration;
    const std::size_t n = footprints_.size();
    host_.info("fem: receptance from " + std::to_string(n) + " impulse responses of " +
               format(duration) + " s (" + format(std::ceil(duration / dt)) + " steps of " +
               format(dt) + " s each, " + std::to_string(op_->threads()) + " thread(s))");
    const auto start = std::chrono::steady_clock::now();
    auto last_check = start;
    auto responses = std::make_unique<rumble::fem::ImpulseReceptance>(
        *op_, weights_, dt, duration, settings_.mesh.f_max,
        [&](std::size_t j, std::size_t k) {
          const auto now = std::chrono::steady_clock::now();
          if (now - last_check > std::chrono::milliseconds(100)) {  // Ctrl-C, as in advance()
            host_.check_stop(static_cast<double>(j) / n);
            last_check = now;
          }
          if (k != 0 || j == 0 || j % std::max<std::size_t>(1, n / 10) != 0) return;  // ~10 %
          const double elapsed = seconds_since(start);
          host_.info("fem: impulse response " + std::to_string(j + 1) + " of " + std::to_string(n) +
                     ", about " + format(elapsed / j * static_cast<double>(n - j), 2) + " s left");
        },
        far, far_lag_.tau);
    host_.info("fem: impulse responses done in " + format(seconds_since(start), 3) +
               " s; the motion in the records' last tenth is " +
               format(responses->decay_ratio(), 2) + " of its peak");
    constexpr double kCutOff = 0.01;  // beyond, the low frequencies carry the truncation
    if (responses->decay_ratio() > kCutOff)
      host_.warn("fem: params/receptance/duration " + format(duration) +
                 " s: the footprints still move at " + format(responses->decay_ratio(), 2) +
                 " of their peak when the records end; the low frequencies are cut off: raise it");
    return responses;
  }

  rumble::fem::PmlProfile pml_profile() const {
    return plan_.physical_box(settings_.boundary.pml_reflection, settings_.boundary.pml_shift());
  }

  /// The layer's memory variables have no place in M, C, K yet.
  void refuse_with_pml(const std::string& what) const {
    if (op_->pml())
      throw std::invalid_argument(
          "fem: params/boundary/type: the perfectly matched layer has no form for " + what +
          " yet; use boundary.type \"viscous_spring\" for it");
  }

  double max_step() const {
    return implicit_ ? settings_.implicit_step : settings_.courant * op_->stable_step();
  }

  /// Before a large Delaunay meshing: the faster algorithm exists. Measured on the stiff example
  /// at about 1e6 DOFs (docs/fem-soil.md section 7): Delaunay 62-95 s on one thread, HXT with 2
  /// threads 4.4 s (and about 20 % fewer tetrahedra for the same sizes).
  void hint_fast_meshing() const {
    constexpr double kLargeMeshDofs = 2e5;  // where Delaunay takes more than about 15 s
    if (settings_.mesh.fast_algorithm || 3.0 * plan_.estimated_nodes < kLargeMeshDofs) return;
    host_.info("fem: meshing about " + format(3.0 * plan_.estimated_nodes) +
               " DOFs with gmsh's delaunay (about 1e4 DOFs per second, one thread); "
               "params/mesh/algorithm \"hxt\" with mesh/threads 2 meshed 1e6 DOFs 15x faster "
               "(its mesh differs slightly from run to run; cached meshes are reused either way)");
  }

  rumble::fem::TetMesh cached_or_new_mesh() const {
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

  /// out = B (F(tau) - reference): consistent nodal forces of the footprint pressures [N].
  void footprint_forces(const rumble::Waveform& force, double tau, Eigen::VectorXd& out,
                        const double* reference) const {
    for (const auto& footprint : weights_)
      for (const rumble::fem::NodalWeight& w : footprint) out[3 * w.node + 2] = 0.0;
    for (std::size_t j = 0; j < weights_.size(); ++j) {
      const double F = force.at(j, tau) - reference[j];
      for (const rumble::fem::NodalWeight& w : weights_[j]) out[3 * w.node + 2] += w.weight * F;
    }
  }

  /// f += the half-space's traction beyond the truncation surface under the footprint forces
  /// (static_far_field.hpp): the static state is the half-space's, not the springs'.
  void add_static_far_field(const double* force, Eigen::VectorXd& f) {
    if (const rumble::fem::StaticFarField* far = far_field()) far->add(force, f);
  }

  /// The far field (static_far_field.hpp), built at the first call after a layout; nullptr
  /// where it does not apply (a layered soil, Liu's springs, no springs).
  const rumble::fem::StaticFarField* far_field() {
    if (!rumble::fem::static_far_field_applies(settings_)) return nullptr;
    if (!far_field_) {
      const auto start = std::chrono::steady_clock::now();
      far_field_.emplace(mesh_, settings_, footprints_, op_->boundary());
      // Its traction changes with the forces, so a force jump acts at its nodes too.
      std::vector<std::int32_t> loaded = rumble::fem::loaded_nodes(weights_);
      loaded.insert(loaded.end(), far_field_->nodes().begin(), far_field_->nodes().end());
      std::sort(loaded.begin(), loaded.end());
      loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
      op_->set_loaded_nodes(std::move(loaded));
      far_lag_.tau =
          far_field_->mean_distance() /
          rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space).shear;
      far_lag_.lagged.assign(footprints_.size(), 0.0);
      far_change_.assign(footprints_.size(), 0.0);
      far_step_.assign(footprints_.size(), 0.0);
      host_.log(RUMBLE_LOG_DEBUG,
                "fem: the half-space's static far field in " + format(seconds_since(start), 2) +
                    " s, " + format(far_field_->bytes() / 1048576.0) +
                    " MiB; it follows the forces with a lag of " + format(far_lag_.tau, 3) + " s");
    }
    return &*far_field_;
  }

  /// The boundary's traction follows the footprint forces' change from the static state, lagged
  /// (FarFieldLag, docs/fem-soil.md §3.2): held over the macro step, its jump at the step's
  /// start acts as the footprints' does.
  void follow_far_field(const rumble::Waveform& force, double H) {
    for (std::size_t j = 0; j < footprints_.size(); ++j) {
      far_change_[j] = force.at(j, 0.5) - force_static_[j];
      far_step_[j] = far_lag_.lagged[j];
    }
    far_lag_.advance(far_change_, H);
    for (std::size_t j = 0; j < footprints_.size(); ++j)
      far_step_[j] = far_lag_.lagged[j] - far_step_[j];
    far_field_->set(far_step_.data(), df_);
    far_field_->set(far_lag_.lagged.data(), f_);
  }

  void spread(const double* force, Eigen::VectorXd& out) const {
    out.setZero();
    for (std::size_t j = 0; j < weights_.size(); ++j)
      for (const rumble::fem::NodalWeight& w : weights_[j])
        out[3 * w.node + 2] += w.weight * force[j];
  }

  /// Area average of the vertical component of x over footprint j.
  double average(std::size_t j, const Eigen::VectorXd& x) const {
    return rumble::fem::footprint_average(weights_[j], x.data());
  }

  void record_probes(double t) {
    if (probes_.empty()) return;
    if (sample_interval_ > 0.0) {
      if (next_sample_ < 0.0) next_sample_ = t;
      if (t < next_sample_ - 1e-9 * sample_interval_) return;
      next_sample_ +=
          sample_interval_ * std::max(1.0, std::floor((t - next_sample_) / sample_interval_) + 1.0);
    }
    for (std::size_t p = 0; p < probes_.size(); ++p) {
      double* out = row_.data() + p * RUMBLE_PROBE_VALUES;
      for (int c = 0; c < 6; ++c) out[c] = 0.0;
      for (int a = 0; a < 4; ++a) {
        const std::int64_t node = probes_[p].nodes[a];
        const double w = probes_[p].weights[a];
        for (int c = 0; c < 3; ++c) {
          out[c] += w * state_.v[3 * node + c];
          out[3 + c] += w * (u_static_[3 * node + c] + state_.w[3 * node + c]);
        }
      }
    }
    samples().push(t, row_.data());
  }

  /// mesh.export: the generated mesh as a .msh that mesh.file reads back, written as a new file
  /// inside the results directory once the soil has one (issue 30): never while it has none
  /// (`rumble validate`, a study's checks, soil-frf, calibrate).
  void export_if_due() {
    if (!export_due_ || host_.results_dir().empty()) return;
    export_due_ = false;
    const std::string where =
        "fem: params/mesh/export: " + nlohmann::json(settings_.mesh.export_file).dump();
    const std::filesystem::path path = rumble::fem::new_results_file(
        host_.results_dir(), settings_.mesh.export_file, where);  // made empty, never replaced
    std::string why;
    try {
      rumble::fem::write_mesh_file(mesh_, settings_, footprints_, path.string());
    } catch (const std::exception& e) {
      why = std::string(" (") + e.what() + ")";
    }
    std::error_code error;
    if (!why.empty() || std::filesystem::file_size(path, error) == 0) {
      std::filesystem::remove(path, error);  // the file made above, not left empty
      throw std::runtime_error(where + ": could not write the mesh to " + path.string() + why +
                               "; check that its folder can be written, or give another path");
    }
    host_.info("fem: mesh written to " + path.string() + " (mesh.file reads it back)");
  }

  /// Chooses the local steps for macro steps of H [s] (the first one's: later changes of H keep
  /// them, stable at any shorter step) and logs the choice or why there is none.
  void enable_local_steps(double H) {
    const double single = op_->single_rate_step(), layer_limit = op_->layer_step_limit();
    std::ostringstream m;
    m << "fem: local time stepping (integrator.local_steps " << settings_.local_steps << "): ";
    const auto start = std::chrono::steady_clock::now();
    const rumble::fem::LocalTimeStepping* lts =
        op_->enable_local_steps(settings_.local_steps, H, settings_.courant) ? op_->local_steps()
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
      host_.warn(m.str());
      return;
    }
    m << lts->fine_nodes() << " fine nodes ("
      << format(100.0 * static_cast<double>(lts->fine_nodes()) / mesh_.node_count(), 2) << " % of "
      << mesh_.node_count() << "; " << lts->halo().size() << " with their neighbours) take "
      << lts->substeps() << " steps per soil step; stable step " << format(op_->stable_step())
      << " s against " << format(single) << " s on one rate (x"
      << format(op_->stable_step() / single, 3) << "): " << std::ceil(H / max_step() - 1e-9)
      << " sub-steps per macro step of " << format(H) << " s instead of "
      << std::ceil(H / (settings_.courant * single) - 1e-9) << " (chosen in " << format(seconds, 2)
      << " s)";
    host_.info(m.str());
  }

  void report(double mesh_seconds, double setup_seconds) const {
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
      << format(static_cast<double>(op_->bytes()) / op_->dofs(), 3) << " B per DOF); stable step "
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

  // The explicit step just taken lasted `took`: the tuner may move the next to another team.
  void tune_threads(std::chrono::steady_clock::duration took) {
    tuner_.record(std::chrono::duration<double>(took).count());
    if (tuner_.threads() != op_->threads()) {
      host_.log(RUMBLE_LOG_DEBUG, "fem: the explicit step goes on " +
                                      std::to_string(tuner_.threads()) +
                                      " thread(s), the fastest now");
      op_->set_threads(tuner_.threads());
    }
  }

  rumble::fem::FemSettings settings_;
  std::string params_;  // the params as validated, one line (part of the receptance cache key)
  rumble::Host host_;
  std::string mesh_file_;  // mesh.file found from the scenario's folder; "" when meshing
  std::vector<rumble::Footprint> footprints_;
  rumble::fem::MeshPlan plan_;
  rumble::fem::TetMesh mesh_;
  rumble::fem::FootprintWeights weights_;
  std::optional<rumble::fem::ExplicitSolver> op_;
  std::unique_ptr<rumble::fem::StaticSolver> statics_;
  std::optional<rumble::fem::StaticFarField> far_field_;  // at the first static solve
  rumble::fem::FarFieldLag far_lag_;                      // how its traction follows the forces
  std::vector<double> far_change_, far_step_;             // scratch [N] per footprint
  std::unique_ptr<rumble::fem::ImplicitSolver> implicit_;
  std::unique_ptr<rumble::fem::Receptance> receptance_;
  std::unique_ptr<rumble::fem::ImpulseReceptance> impulse_;
  std::optional<std::uint64_t> receptance_key_;  // receptance_cache.hpp, once per layout
  bool receptance_cache_warned_ = false;
  bool export_due_ = false;  // mesh.export: the mesh is written at the first call in a run
  ExplicitState state_;
  Eigen::VectorXd u_static_;                       // [m] under force_static_
  Eigen::VectorXd f_, df_;                         // scratch: nodal forces [N]
  std::vector<double> force_static_, force_last_;  // [N] per footprint
  std::vector<rumble::fem::ProbePoint> probes_;
  std::vector<double> probe_resolution_;  // Hz, per probe (resolved_band.hpp)
  std::vector<double> row_;
  double sample_interval_ = 0.0, next_sample_ = -1.0;  // s
  double reported_macro_step_ = -1.0;                  // s: the stepping is logged per H
  bool local_steps_chosen_ = false;                    // integrator.local_steps: at the first H
  rumble::fem::ThreadTuner tuner_;                     // the explicit step's team size
  std::array<Checkpoint, RUMBLE_CHECKPOINT_SLOTS> checkpoints_;
};

}  // namespace

RUMBLE_PLUGIN("fem", "0.2.0", FemSoil)
