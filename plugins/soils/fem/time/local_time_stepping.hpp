// Local time stepping for the explicit step: the stiffest nodes, where a few short elements set
// the stable step, take p steps of a Chebyshev recurrence inside each soil step, the rest one.
// This is the leapfrog LTS of Diaz & Grote (SIAM J. Sci. Comput. 31, 2009) in its stabilized
// form (Grote, Mehlin & Sauter, SIAM J. Numer. Anal. 56, 2018). The soil step stays the central
// difference of explicit_solver.hpp, its residual K y + S w - f at the fine nodes' halo filtered
// by apply(), so that in operator form K is replaced by
//   K_p = -(2 / dt^2) M R(A P) A,   A = M^-1 K,   P the projector on the fine nodes,
//   R(l) = (Q(l) - 1) / l,   Q(l) = T_p(w0 - w1 l) / tau,   tau = T_p(w0),
//   w1 = dt^2 tau / (2 T_p'(w0))   (so that Q(l) = 1 - dt^2 l / 2 + O(l^2)).
// Hence:
// - K_p = K on every row that no fine node touches (R(0) = -dt^2 / 2); elsewhere K_p - K is
//   O(dt^2), so the scheme stays second order;
// - K_p is symmetric (M (A P)^j A = K (P M^-1 K)^j), so the step keeps a shadow energy and its
//   stable step comes from the largest eigenvalue of M^-1 K_p, by the same eigenvalue iteration;
// - with every node fine, K_p = (2 / dt^2) M (I - Q(A)): while w0 - w1 l >= -1 (l up to
//   fine_range()), |Q| <= 1 / tau, so dt^2 l(M^-1 K_p) <= 2 (1 + 1 / tau). tau = 1 is the
//   original LTS, whose resonant modes sit exactly at the stability limit dt^2 l = 4; tau > 1
//   keeps them inside, far enough for the stiffness-proportional damping, which lags half a
//   step (explicit_solver.hpp), to stay stable (tau_for(), below).
// Cost per soil step: the one product with K the step makes anyway, plus p - 1 products of K's
// rows at the halo (the fine nodes and their neighbours) with its columns at the fine nodes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "operator/csr_matrix.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class LocalTimeStepping {
 public:
  /// fine: per node, takes the p sub-steps (fixed nodes never do). substeps p >= 2.
  /// single_precision: K's blocks rounded to float, as the step reads them (StepPrecision), so
  /// that K_p stays symmetric. The halo from K's rows (whole on one process).
  LocalTimeStepping(const CsrMatrix& K, const Eigen::VectorXd& mass, const std::vector<char>& fine,
                    const std::vector<char>& fixed, int substeps, bool single_precision = false);
  /// K's blocks, each once, in SoilOperator::for_each_step_block's form: blocks(visit).
  using Blocks = std::function<void(const SoilOperator::BlockVisit&)>;
  /// The same from K as the step reads it, block by block (`blocks`: a rank's part's, partial at
  /// its shared nodes; no rows assembled), with the halo given: per node, halo_flags() of K's
  /// whole rows (SoilOperator::flagged_neighbours).
  LocalTimeStepping(const Blocks& blocks, const Eigen::VectorXd& mass,
                    const std::vector<char>& fine, const std::vector<char>& halo,
                    const std::vector<char>& fixed, int substeps);
  /// Per node: in the halo (a free node that is fine or K couples to a free fine node), from
  /// fine_neighbours, per node the free fine nodes K couples it to.
  static std::vector<char> halo_flags(const std::vector<char>& fine, const std::vector<char>& fixed,
                                      const std::vector<std::int32_t>& fine_neighbours);
  /// On a rank's part, whose rows at its shared nodes [0, shared_nodes) are partial
  /// (distributed/part_stiffness.hpp): each of the recurrence's products summed over the ranks
  /// there by `sum` (SoilOperator::sum_shared_nodes: 3 values per shared node; called by one
  /// thread of the team), so that every copy of a halo node holds K's whole product.
  void sum_over_ranks(std::int32_t shared_nodes, std::function<void(double*, int)> sum);

  int substeps() const { return p_; }
  std::int64_t fine_nodes() const { return fine_count_; }
  /// The fine nodes, then the other free nodes with a fine neighbour: the rows where K_p != K.
  const std::vector<std::int32_t>& halo() const { return halo_; }

  /// The step dt [s] and the stabilization tau >= 1 (T_p(w0)); call before apply().
  void set_step(double dt, double tau);
  double step() const { return dt_; }
  double tau() const { return tau_; }
  /// The largest eigenvalue of M^-1 K [1/s^2] whose mode the recurrence keeps bounded at this
  /// step: w0 - w1 l >= -1, l <= (1 + w0) / w1; with tau = 1, (2 p / dt)^2.
  double fine_range() const { return fine_range(dt_, tau_, p_); }
  static double fine_range(double dt, double tau, int substeps);

  /// The smallest tau that keeps the half-step lag of the damping a1 K stable for every mode the
  /// bound 2 (1 + 1/tau) allows, with the margin `margin` on its eigenvalue; 0 when no tau can.
  /// A mode with c = dt^2 l / 4 is stable under that lag when c <= 1 / (1 + 2 a1 / dt).
  static double tau_for(double dt, double a1, double margin = 0.9);

  /// forces: a force at the halo nodes [N] (3 per node, in halo() order), replaced by its
  /// filtered form -(2 / dt^2) M R(A P) M^-1 forces; for K y that is K_p y. The step passes its
  /// whole residual K y + S w - f, so that a held load settles where K u = f. Uses orphaned
  /// OpenMP loops: inside a parallel region its threads share the work, outside it runs alone.
  /// On a rank's part (sum_over_ranks), collective: every rank calls it with its halo's forces.
  void apply(double* forces) const;

  std::size_t bytes() const;

 private:
  int p_;
  std::int64_t fine_count_ = 0;
  std::vector<std::int32_t> halo_;
  std::vector<double> inv_mass_;  // per halo node [1/kg]
  // K's blocks at halo rows and fine columns: per halo node, [start_[h], start_[h+1]) entries
  // of (fine position, 9 values row-major) [N/m].
  std::vector<std::int64_t> start_;
  std::vector<std::int32_t> column_;
  std::vector<double> block_;
  double dt_ = 0.0, tau_ = 1.0, w0_ = 1.0, w1_ = 0.0;
  std::vector<double> t_;                                    // T_k(w0), k = 0..p
  mutable std::vector<double> g_, s_prev_, s_cur_, s_next_;  // 3 per halo node
  mutable std::vector<double> product_;  // 3 per halo node on a rank's part (sum_over_ranks)
  // On a rank's part (sum_over_ranks): the halo's shared nodes (their place in halo_), their
  // products gathered per shared node (3 each, zero elsewhere) and the sum over the ranks.
  std::vector<std::int32_t> shared_halo_;
  mutable std::vector<double> shared_products_;
  std::function<void(double*, int)> sum_;
};

}  // namespace rumble::fem
