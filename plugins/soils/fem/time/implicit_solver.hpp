// Newmark's average-acceleration scheme (beta = 1/4, gamma = 1/2: unconditionally stable, second
// order, no numerical damping) on the same equations as ExplicitSolver, for meshes with a few
// elements much smaller than the waves need (docs/numerics.md §1: implicit pays only there):
//   K_eff w' = f' + M (c0 w + c2 v + c3 a) + C (c1 w + c4 v + c5 a),
//   K_eff = K + S + c0 M + c1 C,  C = a0 M + a1 K + D,
// and with op's Maxwell mechanisms (a0 = a1 = 0) K's factor 1 + sum c_l g_l and K h on the right
// (implicit_solver.cpp), their memory stepped as the explicit step does,
// with one CHOLMOD factor of K_eff per step size, reused for every step of that size.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "time/explicit_solver.hpp"

namespace rumble::fem {

class ImplicitSolver {
 public:
  /// The operators of op (K, M, boundary, fixed nodes); a0 [1/s], a1 [s] Rayleigh coefficients.
  ImplicitSolver(const ExplicitSolver& op, double a0, double a1);
  ~ImplicitSolver();
  ImplicitSolver(const ImplicitSolver&) = delete;
  ImplicitSolver& operator=(const ImplicitSolver&) = delete;

  /// One step of dt [s] with the external force f [N] at its end. Throws std::runtime_error
  /// when K_eff cannot be factored (out of memory: CHOLMOD's message).
  void step(ExplicitState& s, const Eigen::VectorXd& f, double dt);
  /// Factorizations so far (one per distinct step size).
  int factorizations() const { return factorizations_; }

 private:
  struct Factor;
  const ExplicitSolver& op_;
  double a0_, a1_;
  std::unique_ptr<Factor> factor_;
  double factored_dt_ = -1.0;
  int factorizations_ = 0;
  Eigen::VectorXd y_, z_, q_, rhs_, ky_;  // scratch
};

}  // namespace rumble::fem
