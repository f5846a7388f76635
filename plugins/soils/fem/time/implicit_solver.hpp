// Newmark's average-acceleration scheme (beta = 1/4, gamma = 1/2: unconditionally stable, second
// order, no numerical damping) on the same equations as ExplicitSolver, for meshes with a few
// elements much smaller than the waves need (docs/numerics.md §1: implicit pays only there):
//   K_eff w' = f' + M (c0 w + c2 v + c3 a) + C (c1 w + c4 v + c5 a),
//   K_eff = K + S + c0 M + c1 C,  C = a0 M + a1 K + D,
// and with op's Maxwell mechanisms (a0 = a1 = 0) K's factor 1 + sum c_l g_l and K h on the right
// (implicit_solver.cpp), their memory stepped as the explicit step does,
// with one factor of K_eff per step size, reused for every step of that size: CHOLMOD's on one
// process, or any EffectiveSystem's (on the ranks PETSc's, distributed/rank_effective_system.hpp:
// every node's update is local, K's product and the solve are the ranks' collective calls).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "operator/effective_matrix.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {

/// Newmark's effective system K_eff w' = r on the soil's nodes (on a rank: its owned and ghost
/// nodes), K_eff a combination of the soil's operators.
class EffectiveSystem {
 public:
  virtual ~EffectiveSystem() = default;
  /// Builds K_eff = c (its factor) for steps of dt [s]; throws std::runtime_error when it
  /// cannot, naming dt.
  virtual void build(const Combination& c, double dt) = 0;
  /// w' at every node, 0 on fixed DOFs, from r's free DOFs (a rank reads its owned nodes').
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& r) = 0;
};

/// K_eff factored by CHOLMOD (supernodal LL^T) on one process.
std::unique_ptr<EffectiveSystem> cholmod_system(const SoilOperator& soil);

class ImplicitSolver {
 public:
  /// The operators of op (K, M, boundary, fixed nodes); a0 [1/s], a1 [s] Rayleigh coefficients;
  /// K_eff solved by `system` (CHOLMOD's on op's soil where null).
  ImplicitSolver(const ExplicitSolver& op, double a0, double a1,
                 std::unique_ptr<EffectiveSystem> system = nullptr);
  ~ImplicitSolver();
  ImplicitSolver(const ImplicitSolver&) = delete;
  ImplicitSolver& operator=(const ImplicitSolver&) = delete;

  /// One step of dt [s] with the external force f [N] at its end. Throws std::runtime_error
  /// when K_eff cannot be factored (out of memory: the system's message). On the ranks every
  /// rank calls it together (K's product and the solve are collective).
  void step(ExplicitState& s, const Eigen::VectorXd& f, double dt);
  /// Factorizations so far (one per distinct step size).
  int factorizations() const { return factorizations_; }

 private:
  const ExplicitSolver& op_;
  double a0_, a1_;
  std::unique_ptr<EffectiveSystem> system_;
  double factored_dt_ = -1.0;
  int factorizations_ = 0;
  Eigen::VectorXd y_, z_, q_, rhs_, ky_;  // scratch
};

}  // namespace rumble::fem
