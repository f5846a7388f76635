// Central-difference time stepping of  M w'' + C w' + K w = f  (velocity Verlet form; second
// order, except first order in the a1 K damping: docs/fem-soil.md §4; docs/numerics.md §4.1) with M
// the lumped mass, C = a0 M + a1 K + D (Rayleigh damping and the boundary's dashpot blocks) and
// K the elastic stiffness plus the boundary's spring blocks:
//   v+ = v + dt/2 a;   w += dt v+;   r = f - K (w + a1 v+) - S w
//   (M + dt/2 (a0 M + D)) v' = M v+ + dt/2 r;   a = 2 (v' - v+) / dt
// Every operator is diagonal or block-diagonal except one K product per step, so a step is one
// pass over K (memory-bound) plus vector updates, split over the threads. The damping terms
// a0 M and D are taken at the new velocity (unconditionally stable); a1 K v+ lags half a step,
// which shortens the stable step as stable_step() says. With the Maxwell mechanisms
// (maxwell_damping.hpp) instead, a0 = a1 = 0 and y = w + sum_l c_l z_l, each memory z_l stepped
// exactly at the new displacement (nothing lags). Fixed nodes never move. With a perfectly
// matched layer (pml.hpp), its tetrahedra add their stretched-minus-elastic forces to K w and its
// nodes their lumped damping (at the new velocity, with a0 M) and springs.
// K, M, S, D and the fixed nodes are the soil operator's (operator/soil_operator.hpp): the step
// reads them through its small interface, K x by one virtual call per thread per step
// (SoilOperator::stepped_product), so that another back end (a distributed one, issue #33) steps
// with this class unchanged (docs/decisions/0006-fem-soil.md). The CSR back end, recognized
// once at construction, is called without it: its fused product takes the node's finish inlined
// (the step is memory-bound, and the handover in runs cost 15-35 % on bench/fem).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "boundary/pml.hpp"
#include "maxwell_damping.hpp"
#include "operator/boundary_blocks.hpp"
#include "operator/csr_matrix.hpp"
#include "operator/csr_operator.hpp"
#include "operator/soil_operator.hpp"
#include "time/local_time_stepping.hpp"

namespace rumble::fem {

struct ExplicitState {
  Eigen::VectorXd w, v, a;  // displacement from the static state [m], velocity, acceleration
  Eigen::VectorXd pml;      // the matched layer's memory variables (pml.hpp); empty: at rest
  // The Maxwell mechanisms' memory z_l [m], DOF by DOF (mechanisms per DOF, adjacent); empty:
  // at rest. Kept in float (a third less traffic per step with three mechanisms): the rounding,
  // 6e-8 of each, is far below the step's O(dt^2) error, as K's (§4.2); the sums are in double.
  Eigen::VectorXf maxwell;
};

class ExplicitSolver {
 public:
  /// K: elastic stiffness; mass per node [kg]; boundary blocks (springs used when
  /// `springs`); fixed: per node, never moves; a0 [1/s], a1 [s]: Rayleigh coefficients;
  /// precision: how the step reads K (the statics and the implicit step read it in double).
  /// The operator's back end is the CSR one (operator/csr_operator.hpp).
  ExplicitSolver(CsrMatrix K, Eigen::VectorXd mass, std::vector<BoundaryNode> boundary,
                 bool springs, std::vector<char> fixed, double a0, double a1, unsigned threads,
                 StepPrecision precision = StepPrecision::kDouble);
  /// The step on any back end of the soil operator, its largest eigenvalue of M^-1 (K + S)
  /// estimated here (Lanczos).
  ExplicitSolver(std::unique_ptr<SoilOperator> op, double a0, double a1);
  /// The same with that eigenvalue known (largest_eigenvalue() of a solver on the same soil,
  /// with the iterations it took; 0: estimated here): a distributed back end's ranks take the
  /// one found over the ranks, so that every rank steps alike (issue #33).
  ExplicitSolver(std::unique_ptr<SoilOperator> op, double a0, double a1, double largest_eigenvalue,
                 int iterations);

  /// The soil operator (K, M, S, D, fixed nodes) the step reads: what the statics, the implicit
  /// step's matrix and the exported matrices take.
  const SoilOperator& soil() const { return *op_; }
  Eigen::Index dofs() const { return op_->dofs(); }
  /// Largest stable step [s]: 2 / omega_max (sqrt(1 + xi^2) - xi), xi = a1 omega_max / 2,
  /// omega_max^2 the largest eigenvalue of M^-1 K from Lanczos iterations (to 1e-9, 2 % margin);
  /// with local time stepping, the longer step it verified (enable_local_steps).
  double stable_step() const {
    return std::min(local_step_ > 0.0 ? local_step_ : single_rate_step_, pml_step_);
  }
  /// The stable step of one rate everywhere [s].
  double single_rate_step() const { return single_rate_step_; }
  /// The matched layer's own limit on the step [s] (its damping; huge without a layer).
  double layer_step_limit() const { return pml_step_; }
  /// The highest circular frequency the step must resolve [rad/s] (with a 2 % margin, and the
  /// Maxwell mechanisms' unrelaxed stiffness).
  double omega_max() const { return omega_max_; }
  int eigen_iterations() const { return eigen_iterations_; }
  /// The largest eigenvalue of M^-1 (K + S) with its 2 % margin [1/s^2].
  double largest_eigenvalue() const { return lambda_max_; }

  /// Local time stepping (local_time_stepping.hpp): the stiffest nodes take `substeps` steps
  /// per soil step. Chooses them from each node's Gershgorin bound, the soil step for the least
  /// work per simulated second, and verifies that step by the largest eigenvalue of M^-1 (K_p + S).
  /// With macro_step H > 0 [s] the soil steps H in whole sub-steps of at most courant x the
  /// stable step: the candidates are then the steps that make n sub-steps, H / (n courant), for
  /// each n below one rate's count, ranked by their work per macro step.
  /// Steps at or below courant x single_rate_step() stay single-rate (so a step between that
  /// and one rate's limit keeps the caller's margin). Returns false (and stays single
  /// rate) when no longer step was found; substeps < 2 switches it off. After set_pml (the
  /// layer's nodes and their neighbours are never fine).
  /// Collective on many ranks (every rank calls it, in the same order).
  bool enable_local_steps(int substeps, double macro_step = 0.0, double courant = 1.0);
  const LocalTimeStepping* local_steps() const { return lts_ ? &*lts_ : nullptr; }
  /// With local time stepping, over the whole soil (on many ranks each node counted once, the
  /// same on every rank: collective): its fine nodes, those with their neighbours, all nodes.
  struct LocalStepNodes {
    double fine = 0.0, halo = 0.0, nodes = 0.0;
  };
  LocalStepNodes local_step_nodes() const;

  /// Damps by the Maxwell mechanisms (constructed with a0 = a1 = 0; before enable_local_steps):
  /// the stable step becomes the unrelaxed stiffness's, omega_max x sqrt(d.unrelaxed()).
  void set_maxwell_damping(MaxwellDamping d);
  const MaxwellDamping& maxwell_damping() const { return maxwell_; }

  /// Adds a perfectly matched layer on the mesh's outer tetrahedra.
  void set_pml(PmlLayer layer);
  const PmlLayer* pml() const { return pml_ ? &*pml_ : nullptr; }

  /// Zero displacement, velocity, acceleration and memory.
  ExplicitState rest_state() const;

  /// One step of dt [s] with the external force f [N] at its end (size dofs()).
  void step(ExplicitState& s, const Eigen::VectorXd& f, double dt) const;
  /// Adds M^-1 df to the acceleration: the external force changed by df at the current time
  /// (read at the loaded nodes, and with local steps at the halo).
  void force_jump(ExplicitState& s, const Eigen::VectorXd& df) const;
  /// The nodes where force jumps act, each once: force_jump() reads df there only, so df must
  /// be zero elsewhere. By default every node. The plugin gives the footprints' nodes, so that
  /// a jump, once per macro step, does not pass over the mesh (10 % of B7's stepping).
  void set_loaded_nodes(std::vector<std::int32_t> nodes);

  /// y = (K + S) x as the step reads K (its precision), filtered by the local steps at the halo
  /// at step dt [s] when they act there: the effective stiffness K_p of local_time_stepping.hpp
  /// (S is zero at the fine nodes).
  void effective_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y, double dt) const;
  /// The operator's (soil_operator.hpp), for the callers that hold the solver.
  void stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs) const {
    op_->stiffness_times(x, y, with_springs);
  }
  void stepped_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                               bool with_springs) const {
    op_->stepped_stiffness_times(x, y, with_springs);
  }
  StepPrecision precision() const { return op_->precision(); }
  const CsrMatrix& stiffness() const { return op_->stiffness(); }
  /// K's rows may be freed between uses and built again by `assemble` (soil_operator.hpp): the
  /// step reads its own copy of K.
  void set_stiffness_source(std::function<CsrMatrix()> assemble) {
    op_->set_stiffness_source(std::move(assemble));
  }
  void release_stiffness() const { op_->release_stiffness(); }
  const std::vector<BoundaryNode>& boundary() const { return op_->boundary(); }
  const std::vector<char>& fixed() const { return op_->fixed(); }
  bool springs_act() const { return op_->springs_act(); }
  const Eigen::VectorXd& mass() const { return op_->mass(); }
  /// The operator's and the step's own memory [bytes].
  std::size_t bytes() const;
  /// Called between the iterations of the long set-up loops (the eigenvalue iterations of
  /// enable_local_steps, the static solver's conjugate gradients): the plugin's Ctrl-C check,
  /// which throws to stop. None by default.
  void set_stop_check(std::function<void()> check) { op_->set_stop_check(std::move(check)); }
  void check_stop() const { op_->check_stop(); }
  /// Threads for the step's loops and the operator's products (the host grants them per run,
  /// after the layout).
  void set_threads(unsigned threads) { op_->set_threads(threads); }
  unsigned threads() const { return op_->threads(); }
  /// Energies of a state [J]: kinetic 1/2 v^T M v and strain 1/2 w^T (K + S) w (K as the step
  /// reads it).
  double kinetic_energy(const ExplicitState& s) const;
  double strain_energy(const ExplicitState& s) const;

 private:
  void estimate_stable_step();
  /// The stable step [s] for the largest eigenvalue lambda [1/s^2] of M^-1 K from Lanczos:
  /// with its 2 % margin, the unrelaxed stiffness of the Maxwell mechanisms and the lag of a1 K.
  double step_limit(double lambda) const;
  /// The largest eigenvalue of M^-1 op over the free DOFs (Lanczos, to 1e-9), from a fixed
  /// pseudo-random start.
  double largest_eigenvalue(const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& op,
                            int& iterations) const;
  // enable_local_steps' parts (local_steps_choice.cpp).
  struct FineGuess;  // which nodes a step makes fine, and what their sub-steps cost
  struct LocalStepCandidate {
    double work, step, safety;  // work relative to one rate's, step [s], the guess's share
  };
  FineGuess guess_fine_nodes() const;
  /// Whether the local steps can take a step of dt [s] at all.
  bool local_step_feasible(double dt, int substeps) const;
  /// The steps worth trying, least work first.
  std::vector<LocalStepCandidate> local_step_candidates(const FineGuess& guess, int substeps,
                                                        double macro_step, double courant) const;
  /// Sets up the local steps at the first candidate whose largest eigenvalue allows its step.
  bool verify_local_steps(const FineGuess& guess, const std::vector<LocalStepCandidate>& candidates,
                          int substeps, double macro_step);
  void drop_local_steps();
  /// The local steps' coefficients for a step of dt [s] (once per distinct dt).
  void prepare_local_steps(double dt) const;
  /// Filters forces [N] (size dofs()) at the halo (local_time_stepping.hpp) on the step's
  /// threads and hands each halo node's filtered force to take(node, force).
  template <class Take>
  void filter_halo(const double* forces, Take&& take) const;
  /// The step's first half, on the team (an orphaned omp for, with its barrier):
  /// v+ = v + dt/2 a, w += dt v+ and y = w + a1 v+ (with the Maxwell mechanisms, their memories
  /// stepped and y = w + sum_l c_l z_l), at every free node.
  void predict(ExplicitState& s, double dt) const;
  /// On a rank's part, inside the step's team after the layer's tetrahedra: their forces at the
  /// nodes other ranks hold too, gathered and summed over the ranks (pml_shared_).
  void sum_pml_over_ranks() const;
  /// Node i's residual force K y + S w - f [N] (y = w + a1 v+) from its K y in `out`.
  void residual(std::int64_t i, const double* w, const Eigen::VectorXd& f, double out[3]) const;
  /// Node i's velocity and acceleration update from its residual (filtered by the local steps
  /// at the halo) [N], with the matched layer's forces and the implicit diagonal damping.
  void finish_node(std::int64_t i, const double residual[3], double dt, ExplicitState& s,
                   double* memory) const;

  std::unique_ptr<SoilOperator> op_;
  const CsrOperator* csr_;  // op_ when it is the CSR back end (the step's fast path), else null
  // The operator's node data, read node by node in the step's loops (no call there): mass per
  // node [kg], boundary blocks, per node the index into them or -1, fixed per node.
  const double* mass_;
  const BoundaryNode* boundary_;
  const std::int32_t* boundary_of_;
  const char* fixed_;
  bool springs_;
  std::vector<std::int32_t> loaded_nodes_;  // set_loaded_nodes()
  bool every_node_loaded_ = true;           // until set_loaded_nodes()
  double a0_, a1_;
  MaxwellDamping maxwell_;   // none unless set_maxwell_damping
  double lambda_max_ = 0.0;  // the largest eigenvalue of M^-1 (K + S) from Lanczos [1/s^2]
  double omega_max_ = 0.0, single_rate_step_ = 0.0;
  double local_step_ = 0.0;      // verified with local time stepping [s]; 0: off
  double one_rate_limit_ = 0.0;  // [s] longer steps are local ones (enable_local_steps)
  double pml_step_ = 1e300;      // the matched layer's own limit [s]
  int eigen_iterations_ = 0;
  mutable Eigen::VectorXd y_;  // scratch: w + a1 v+
  std::optional<PmlLayer> pml_;
  mutable std::vector<double> pml_forces_;  // scratch: 12 per layer tetrahedron [N]
  // On a rank's part: the layer's forces gathered at the nodes other ranks hold too, 3 per node
  // [N], summed over the ranks each step (their tetrahedra are split over the ranks).
  mutable std::vector<double> pml_shared_;
  // Local time stepping; mutable: its coefficients follow the step size the caller asks for.
  mutable std::optional<LocalTimeStepping> lts_;
  std::vector<std::int32_t> halo_of_;        // per node: its place in lts_->halo(), or -1
  mutable std::vector<double> halo_forces_;  // scratch: the residual at the halo [N]
  mutable bool last_step_local_ = false;     // the last step filtered the halo (force_jump)
};

}  // namespace rumble::fem
