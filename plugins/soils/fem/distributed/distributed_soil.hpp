// One rank's share of the FEM soil under `mpirun -n N rumble run` (issue #33;
// docs/decisions/0012-distributed-soil.md; docs/fem-soil.md §8, "On many ranks"): its part of the
// mesh, its operator and explicit step, its state, the footprints' weights, the far field's
// rows and the receivers on its nodes. The plugin makes every call on every rank with the same
// inputs (the host mirrors them). Rank 0 alone holds the whole mesh (with mesh.refine on the
// ranks the coarse mesh, each rank refining its part: refined_partition.hpp), which it hands out
// at the layout; every rank then builds its share from its own part (part_pieces.hpp), the stable
// step by Lanczos over the ranks. Every call is collective.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boundary/static_far_field.hpp"
#include "distributed/mesh_partition.hpp"
#include "distributed/part_pieces.hpp"
#include "distributed/rank_statics.hpp"
#include "fem_settings.hpp"
#include "mesh/pml_profile.hpp"
#include "operator/footprint_loads.hpp"
#include "output/probe_locator.hpp"
#include "statics/petsc_session.hpp"
#include "time/explicit_solver.hpp"
#include "time/implicit_solver.hpp"

namespace rumble::fem {

class DistributedSoil {
 public:
  /// comm: the host's communicator for the soil (a duplicate of MPI_COMM_WORLD). Starts PETSc
  /// (statics/petsc_session.hpp) on every rank at once: its start is collective.
  explicit DistributedSoil(MPI_Comm comm);

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  bool root() const { return rank_ == 0; }
  bool laid_out() const { return step_.has_value(); }

  /// Splits rank 0's mesh (mesh_partition.hpp; nullptr on the other ranks) and builds this
  /// rank's share from its part alone: its operator, boundary blocks and fixed nodes, the
  /// explicit step with the stable step from Lanczos over the ranks (the same on every rank),
  /// and the footprints' weights on its nodes. threads: the products'. refine > 0 (mesh.refine
  /// on the ranks): rank 0's mesh is the coarse mesh, split as it is, and each rank refines its
  /// part `refine` times after the split (refined_partition.hpp); with statics.solver geometric
  /// each rank keeps its coarse part, the multigrid's coarse level (geometric_rank_statics.hpp).
  /// pml: the matched layer's box (boundary.type pml: the whole mesh's, the same on every rank;
  /// part_pml.hpp), or null.
  void lay_out(const TetMesh* mesh, const FemSettings& settings,
               const std::vector<Footprint>& footprints, unsigned threads, int refine = 0,
               const PmlProfile* pml = nullptr);
  /// The whole mesh's DOFs.
  std::int64_t whole_dofs() const { return 3 * part_.global_nodes; }
  /// The levels each rank refined its part by (0: rank 0's mesh split as it is).
  int refined() const { return refine_; }
  /// The far field's rows of this rank's boundary nodes (StaticFarField on its part), where the
  /// settings take one; its nodes take force jumps too. Returns the boundary nodes' mean
  /// distance from the footprints' centre over the whole mesh [m] (0: no far field).
  double set_far_field(const FemSettings& settings, const std::vector<Footprint>& footprints);
  bool has_far_field() const { return far_.has_value(); }
  /// The static state [m] on this rank's nodes.
  void set_static(const Eigen::VectorXd* whole);
  /// The static state solved on the ranks (built at the first call: geometric_rank_statics.hpp
  /// with statics.solver geometric and mesh.refine, else distributed_statics.hpp's GAMG)
  /// under the footprint forces F [N] and the far field's traction; on rank 0 each footprint's
  /// average of it [m] in `averages` (sized by the caller). Returns whether this call built the
  /// solver.
  bool solve_static(const double* F, double* averages);
  /// What the statics' CG calls between its iterations (RankStatics::set_stop_check; the soil
  /// gives rank 0 the host's Ctrl-C check): kept for each solver built.
  void set_stop_check(std::function<void()> check) { stop_check_ = std::move(check); }
  const RankStatics* statics() const { return statics_.get(); }
  const Eigen::VectorXd& static_state() const { return u_static_; }
  /// The receivers, each sampled by the rank whose part holds its tetrahedron (part_pieces.hpp).
  void set_probes(const std::vector<Probe>& probes);
  /// Frees the statics' matrices and multigrid (ABI 1.5's statics_done) and the operator's K
  /// rows (the step reads its upper blocks); the next solve_static builds them again. On every
  /// rank.
  void free_statics() {
    statics_.reset();
    if (step_) step_->release_stiffness();
  }
  /// The largest rank's estimate of its peak resident memory [bytes] over the run (memory_model
  /// .hpp, from what each rank holds after its layout), for ABI 1.5's size.
  double peak_estimate() const { return peak_estimate_; }

  ExplicitSolver& step() { return *step_; }
  /// Newmark's implicit step on the ranks where the settings ask for it (integrator.scheme
  /// implicit: K_eff factored by MUMPS over the ranks, rank_effective_system.hpp), else null.
  ImplicitSolver* implicit() { return implicit_.get(); }

  /// The operator's statics products throw std::runtime_error(why) on this rank from its next
  /// layout's stable step on (DistributedOperator::fail_products_on_purpose):
  /// RUMBLE_FEM_FAIL_RANK_AT's "rank:statics", a test's.
  void fail_products_on_purpose(std::string why) { failing_products_ = std::move(why); }
  const ExplicitSolver& step() const { return *step_; }
  ExplicitState& state() { return state_; }
  const ExplicitState& state() const { return state_; }
  Eigen::VectorXd& force() { return f_; }        // [N] this rank's nodes' force
  Eigen::VectorXd& force_jump() { return df_; }  // [N] its change at a macro step's start
  const FootprintWeights& weights() const { return weights_; }
  const MeshPartition& partition() const { return part_; }
  /// The far field's traction moving from G before to G now at this rank's far-field nodes:
  /// into force() and force_jump() (StaticFarField::follow).
  void follow_far_field(const double* before, const double* now) {
    far_->follow(before, now, f_, df_, step_->threads());
  }

  /// Rank 0: each footprint's average of the displacement from the static state and of the
  /// velocity, summed over the ranks' owned nodes in rank order. Collective.
  void footprint_motion(double* w_average, double* v_average) const {
    footprint_averages(state_.w, state_.v, w_average, v_average);
  }
  /// Rank 0: the receivers' rows (RUMBLE_PROBE_VALUES each, as one process records them; on
  /// the other ranks `rows` is scratch). Collective.
  void sample_probes(double* rows) const;
  /// Rank 0: the whole nodal vector (3 per node of rank 0's mesh) of a vector on every rank's
  /// nodes. Collective.
  void gather(const Eigen::VectorXd& local, Eigen::VectorXd* whole) const;

  /// Rank 0: one line on the partition (tetrahedra, nodes, halo and memory per rank). Collective.
  std::string summary() const;

 private:
  /// This rank's operator and explicit step on its part (lay_out's second half).
  void build_step(const FemSettings& settings, const std::vector<Footprint>& footprints,
                  unsigned threads, const PmlProfile* pml);
  void set_loaded_nodes();
  /// The largest rank's estimate of its run's peak [bytes] from what it holds now.
  double estimate_peak() const;
  /// Rank 0: each footprint's averages of x and y (3 per node), summed in rank order.
  void footprint_averages(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double* x_average,
                          double* y_average) const;

  std::shared_ptr<PetscSession> petsc_;  // (outlives the partition's PETSc objects)
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  MeshPartition part_;
  double split_peak_ = 0.0;  // bytes: this rank's VmHWM once split (rank 0's: meshing included)
  int refine_ = 0;           // mesh.refine on the ranks
  bool aggregation_statics_ = false;  // the statics by aggregation_rank_statics.hpp
  std::int64_t coarse_nodes_ = 0;     // rank 0's mesh, split
  std::optional<ExplicitSolver> step_;
  std::unique_ptr<ImplicitSolver> implicit_;  // (over step_'s operators)
  ExplicitState state_;
  Eigen::VectorXd u_static_, f_, df_;
  FootprintWeights weights_;           // local nodes, owned and ghost
  FootprintWeights owned_weights_;     // local nodes this rank owns
  std::optional<StaticFarField> far_;  // (its rows: this rank's boundary nodes)
  bool far_field_set_ = false;
  double far_mean_distance_ = 0.0;        // m, over the whole mesh
  std::unique_ptr<RankStatics> statics_;  // at the first solve_static of a layout
  std::function<std::unique_ptr<RankStatics>()> make_statics_;  // (lay_out's settings)
  std::function<void()> stop_check_;                            // (set_stop_check's)
  std::unique_ptr<MeshPartition> coarse_;  // statics.solver geometric: the coarse part
  std::vector<PartProbe> probes_;
  std::size_t probe_count_ = 0;
  mutable std::vector<double> probe_rows_;  // sample_probes' rows on this rank
  double peak_estimate_ = 0.0;              // bytes
  std::string failing_products_;            // (fail_products_on_purpose's)
};

}  // namespace rumble::fem
