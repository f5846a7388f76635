// The FEM soil's plugin class, declared once for the files that define its members by concern
// (fem_soil.cpp, fem_layout.cpp, fem_stepping.cpp, fem_outputs.cpp, fem_frequency.cpp,
// fem_distributed.cpp): the class maps the host's calls onto the rooms
// (docs/decisions/0006-fem-soil.md), and in one file that mapping was too long to read or review
// one concern at a time. Private to the plugin: no room includes it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <chrono>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "boundary/static_far_field.hpp"
#include "distributed/distributed_soil.hpp"
#include "distributed/rank_plan.hpp"
#include "fem_settings.hpp"
#include "frequency/impulse_receptance.hpp"
#include "frequency/receptance.hpp"
#include "mesh/mesh_generator.hpp"
#include "mesh/pml_profile.hpp"
#include "mesh/tet_mesh.hpp"
#include "operator/footprint_loads.hpp"
#include "output/probe_locator.hpp"
#include "statics/static_solver.hpp"
#include "time/explicit_solver.hpp"
#include "time/implicit_solver.hpp"
#include "time/thread_tuner.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

class FemSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "fem";
  static constexpr const char* kSummary =
      "3D finite-element half-space meshed with gmsh (linear tetrahedra, Lysmer-Kuhlemeyer "
      "viscous-spring boundary, explicit sub-cycled steps, receivers at any depth, VTU fields)";
  /// Its matrices make it a soil for the monolithic reference (small meshes: the engine holds
  /// them banded) and for `rumble stability`. Under `mpirun -n N` its mesh is split over the N
  /// ranks (fem_distributed.cpp; docs/fem-soil.md, "On many ranks"). It takes any step it is
  /// given (an unstable one stops the run): a coupler need not keep the track's checkpoint for it.
  static constexpr std::uint64_t kCapabilities = rumble::kCapThreads | rumble::kCapLinearMatrices |
                                                 rumble::kCapDistributed | rumble::kCapNeverRefuses;
  static const char* params_schema() { return rumble::fem::settings_schema(); }

  FemSoil(const std::string& params_json, const rumble::Host& host);

  void accept_layout(const std::vector<rumble::Footprint>& footprints) override;
  void initialize(double /*t0*/, const double* static_force, double* static_u) override;
  void finalize() override;
  void advance(double t, double H, const rumble::Waveform& force) override;
  void motion(double* u, double* v) const override;
  void set_probes(const std::vector<rumble::Probe>& probes, double sample_interval) override;
  std::vector<double> probe_resolution(std::string& rule) const override;
  void write_fields(double t, const std::string& path) override;
  bool frequency_response(double f_hz, std::complex<double>* receptance) override;
  void linear_matrix(rumble_matrix which, rumble::CscMatrix& out) override;
  void wave_speeds(double& c_s_min, double& c_r_min) const override;
  /// DOFs and the estimate of a run's peak memory made at the layout (memory_model.hpp).
  /// On many ranks: the whole mesh's DOFs and the largest rank's estimate of its peak
  /// (docs/fem-soil.md §8).
  Size size() const override {
    if (distributed_)
      return {distributed_->laid_out() ? static_cast<std::uint64_t>(distributed_->whole_dofs()) : 0,
              peak_estimate_};
    return {op_ ? static_cast<std::uint64_t>(op_->dofs()) : 0, peak_estimate_};
  }
  void statics_done() override {
    if (distributed_) {  // GAMG's matrix and hierarchy; rank 0's whole operator and factor
      distributed_->free_statics();
      return free_whole_on_root();
    }
    if (statics_) free_statics();
  }

  /// [m/s] the slowest layer's Rayleigh speed: the mesh's sizes follow its wavelength.
  double rayleigh_speed() const {
    return rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space).rayleigh;
  }

  void checkpoint_save(std::uint32_t slot) override;
  void checkpoint_restore(std::uint32_t slot) override;
  void checkpoint_free(std::uint32_t slot) override { checkpoints_.at(slot) = {}; }

 private:
  struct Checkpoint {
    ExplicitState state;
    std::vector<double> force_last;
    std::vector<double> far_lagged;  // FarFieldLag::lagged
    double next_sample = -1.0;
    bool valid = false;
  };

  /// x with `digits` significant digits, as the soil's messages write numbers.
  static std::string format(double x, int digits = 3);

  static double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void require_layout(const char* call) const {
    if (!op_ && !(distributed_ && distributed_->laid_out()))
      throw std::logic_error(std::string("fem: ") + call + "() before accept_layout()");
  }

  // One process's work, which on many ranks rank 0 does on the whole mesh
  // (fem_distributed.cpp).
  void lay_out_here(const std::vector<rumble::Footprint>& footprints);
  /// lay_out_here's halves: the mesh (generated, cached or read), then the operators on it
  /// (mesh_seconds: the first's time; start: the layout's).
  void mesh_here(const std::vector<rumble::Footprint>& footprints);
  void build_here(const std::vector<rumble::Footprint>& footprints, double mesh_seconds,
                  std::chrono::steady_clock::time_point start);
  void initialize_here(double t0, const double* static_force, double* static_u);
  /// The host's Ctrl-C check (throws rumble::Stopped), asked every 0.1 s at most: inside the
  /// static solves and the local steps' choice (on many ranks rank 0's, in the ranks' CG).
  std::function<void()> throttled_stop_check();
  void set_probes_here(const std::vector<rumble::Probe>& probes, double sample_interval);

  // On many ranks (fem_distributed.cpp): the same calls on every rank's share.
  /// Under a launcher of more than one rank: this rank's share (distributed_), after refusing
  /// what does not run on many ranks yet.
  void join_ranks();
  void refuse_on_many_ranks() const;
  void accept_layout_distributed(const std::vector<rumble::Footprint>& footprints);
  void initialize_distributed(double t0, const double* static_force, double* static_u);
  /// The static state solved on the ranks (statics.solver gamg: distributed_statics.hpp;
  /// geometric: geometric_rank_statics.hpp).
  void solve_static_on_ranks(const double* static_force, double* static_u);
  void advance_distributed(double t, double H, const rumble::Waveform& force);
  /// The footprints' forces on this rank's nodes (as footprint_forces).
  void distributed_forces(const rumble::Waveform& force, double tau, Eigen::VectorXd& out,
                          const double* reference) const;
  void follow_far_field_distributed(const rumble::Waveform& force, double H);
  void motion_distributed(double* u, double* v) const;
  void set_probes_distributed(const std::vector<rumble::Probe>& probes, double sample_interval);
  void write_fields_distributed(double t, const std::string& path);
  /// Rank 0's whole operator and what was built on it for its statics, freed once the ranks
  /// hold the static state (the whole mesh stays: the fields and the receivers' resolution).
  void free_whole_on_root();
  /// What needs the whole operator, refused on many ranks: `what` names the call.
  void refuse_whole_operator(const std::string& what) const;
  /// The state the steps advance: this rank's share on many ranks.
  ExplicitState& stepped_state() { return distributed_ ? distributed_->state() : state_; }

  /// One explicit run per footprint (impulse_receptance.hpp), with progress and Ctrl-C.
  std::unique_ptr<rumble::fem::ImpulseReceptance> impulse_responses();

  rumble::fem::PmlProfile pml_profile() const {
    return plan_.physical_box(settings_.boundary.pml_reflection, settings_.boundary.pml_shift());
  }

  /// The layer's memory variables have no place in M, C, K yet.
  void refuse_with_pml(const std::string& what) const;

  double max_step() const {
    return implicit_ ? settings_.implicit_step : settings_.courant * op_->stable_step();
  }

  /// Before a large Delaunay meshing: the faster algorithm exists. Measured on the stiff example
  /// at about 1e6 DOFs (docs/fem-soil.md section 7): Delaunay 62-95 s on one thread, HXT with 2
  /// threads 4.4 s (and about 20 % fewer tetrahedra for the same sizes).
  /// `rumble mesh --ranks N` (distributed/rank_plan.hpp): the estimate per rank in the log.
  void report_ranks(double nodes, const char* source) const;
  /// `rumble mesh --ranks N` once meshed: the mesh split on this process, its counts and the
  /// memory per rank from them in the log (distributed/split_plan.hpp).
  void report_split() const;
  void hint_fast_meshing() const;

  rumble::fem::TetMesh cached_or_new_mesh() const;
  void refine_here(const std::vector<rumble::Footprint>& footprints);  // mesh.refine here
  /// mesh.refine: warns when gmsh's coarse size near the track is wider than a footprint.
  void warn_if_coarse_near_track(const std::vector<rumble::Footprint>& footprints) const;
  /// mesh.refine on many ranks: the levels each rank refines its part by after the split (0:
  /// none, or a mesh.file).
  int refine_on_ranks() const { return settings_.mesh.file.empty() ? settings_.mesh.refine : 0; }
  /// What the settings choose that a rank's memory depends on (distributed/rank_plan.hpp).
  rumble::fem::PlanChoices plan_choices() const {
    return {settings_.statics_named, refine_on_ranks(), settings_.geometric_statics,
            settings_.implicit, settings_.aggregation_statics};
  }
  /// The refined mesh's node count, from rank 0's coarse mesh (numbered_refinement.hpp).
  double refined_node_count() const;
  /// Rank 0, below the factor limit with mesh.refine on the ranks: the whole coarse mesh refined
  /// as one process refines it (for the static factor), and each node's number on the ranks.
  void refine_whole_on_root();

  /// out = B (F(tau) - reference): consistent nodal forces of the footprint pressures [N].
  void footprint_forces(const rumble::Waveform& force, double tau, Eigen::VectorXd& out,
                        const double* reference) const;

  /// f += the half-space's traction beyond the truncation surface under the footprint forces
  /// (static_far_field.hpp): the static state is the half-space's, not the springs'.
  void add_static_far_field(const double* force, Eigen::VectorXd& f);

  /// The far field (static_far_field.hpp), built at the first call after a layout; nullptr
  /// where it does not apply (a layered soil, Liu's springs, no springs).
  const rumble::fem::StaticFarField* far_field();

  /// The boundary's traction follows the footprint forces' change from the static state, lagged
  /// (FarFieldLag, docs/fem-soil.md §3.2): held over the macro step, its jump at the step's
  /// start acts as the footprints' does.
  void follow_far_field(const rumble::Waveform& force, double H);

  void spread(const double* force, Eigen::VectorXd& out) const;

  /// Area average of the vertical component of x over footprint j.
  double average(std::size_t j, const Eigen::VectorXd& x) const {
    return rumble::fem::footprint_average(weights_[j], x.data());
  }

  void record_probes(double t);

  /// mesh.export: the generated mesh as a .msh that mesh.file reads back, written as a new file
  /// inside the results directory once the soil has one (issue 30): never while it has none
  /// (`rumble validate`, a study's checks, soil-frf, calibrate).
  void export_if_due();

  /// Chooses step's local steps for macro steps of H [s] (the first one's: later changes of H
  /// keep them, stable at any shorter step) and logs the choice or why there is none (`speak`:
  /// on many ranks rank 0 alone). Collective on many ranks.
  void enable_local_steps(rumble::fem::ExplicitSolver& step, double H, bool speak);

  void report(double mesh_seconds, double setup_seconds) const;
  /// The run's peak resident memory [bytes], estimated from what is resident now, the peak so far
  /// (the meshing's) and the statics' path on this matrix (memory_model.hpp), for size() and
  /// the report.
  double estimate_peak() const;

  /// What only the statics need, freed at the first step after them: the static solver's
  /// factor or multigrid hierarchy, and K's rows when the step reads its own copy
  /// (docs/fem-soil.md section 7.2: the stepping phase's memory).
  void free_statics();

  // The explicit step just taken lasted `took`: the tuner may move the next to another team.
  void tune_threads(std::chrono::steady_clock::duration took);

  rumble::fem::FemSettings settings_;
  std::string params_;  // the params as validated, one line (part of the receptance cache key)
  rumble::Host host_;
  std::string mesh_file_;  // mesh.file found from the scenario's folder; "" when meshing
  std::vector<rumble::Footprint> footprints_;
  rumble::fem::MeshPlan plan_;
  rumble::fem::TetMesh mesh_;
  // statics.solver geometric: gmsh's mesh before mesh.refine (the multigrid's coarse level).
  rumble::fem::TetMesh coarse_mesh_;
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
  bool statics_to_free_ = false;                       // a static solve since the last step
  double peak_estimate_ = 0.0;                         // bytes: estimate_peak() at the layout
  rumble::fem::ThreadTuner tuner_;                     // the explicit step's team size
  std::array<Checkpoint, RUMBLE_CHECKPOINT_SLOTS> checkpoints_;
  // On many ranks: this rank's share of the soil; null on one process.
  std::unique_ptr<rumble::fem::DistributedSoil> distributed_;
  std::vector<double> static_average_;  // [m] per footprint, on rank 0: the static state's
  // The statics on rank 0's whole mesh (a CHOLMOD factor, below its limit without statics.solver
  // gamg, as one process solves them); else GAMG on the ranks.
  bool statics_on_root_ = false;
  // Rank 0's whole refined mesh (refine_whole_on_root): per node, its number on the ranks.
  std::vector<std::int32_t> whole_numbers_;
  // RUMBLE_FEM_FAIL_RANK_AT ("rank:seconds", a test's): the rank whose steps fail from then on.
  int fail_rank_ = -1;
  double fail_at_ = 0.0;
};

}  // namespace rumble::fem
