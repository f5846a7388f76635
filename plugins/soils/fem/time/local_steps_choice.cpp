// ExplicitSolver::enable_local_steps: which nodes take the sub-steps and at what soil step
// (docs/fem-soil.md section 4.1). Each node's Gershgorin bound guesses the stiff ones, the
// candidates are ranked by their work, and the first whose largest eigenvalue allows its step is
// kept.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "time/explicit_solver.hpp"

namespace rumble::fem {

/// Which nodes a step makes fine, from each node's Gershgorin bound of M^-1 K scaled so that the
/// largest is the mesh's largest eigenvalue, and what their extra sub-steps cost.
struct ExplicitSolver::FineGuess {
  const SoilOperator& op;
  const char* fixed;
  double a1;
  std::vector<double> bound;         // per node [1/s^2], unscaled
  double scale = 0.0;                // lambda_max / the largest bound
  std::vector<char> may_be_fine;     // per node
  std::vector<std::int32_t> degree;  // per node: the blocks in its row of K (whole rows)
  double blocks = 0.0;               // K's blocks

  static constexpr double kSafety = 0.7;  // a node is fine above this share of the coarse limit

  /// The fine nodes at step dt [s]: those whose scaled bound exceeds `safety` times the coarse
  /// nodes' limit.
  std::vector<char> fine_at(double dt, double safety) const {
    // The coarse nodes' limit: c = dt^2 l / 4 <= 0.9 / (1 + 2 a1 / dt) (tau_for's margin).
    const double coarse_limit = 4.0 / (dt * dt) * 0.9 / (1.0 + 2.0 * a1 / dt);
    const auto n = static_cast<std::int64_t>(bound.size());
    std::vector<char> fine(n, 0);
    for (std::int64_t i = 0; i < n; ++i)
      fine[i] = may_be_fine[i] && scale * bound[i] > safety * coarse_limit;
    return fine;
  }

  /// The work of one extra sub-step relative to a pass over K: its product reads K's blocks at
  /// the halo's rows (the fine nodes and their neighbours) and the fine nodes' columns, and its
  /// vector updates cost about a quarter of a pass over the halo's rows (measured on the 1e6-DOF
  /// medium mesh: 7.5 % per step for a halo of 18.6 % of the nodes, 3.5 % fine, p = 2). Counted
  /// on K's whole rows and each node once, so the same on any number of ranks (collective).
  double extra_work(const std::vector<char>& fine) const {
    const std::vector<std::int32_t> fine_columns = op.flagged_neighbours(fine);
    std::vector<double> halo_blocks(bound.size(), 0.0);
    for (std::size_t i = 0; i < bound.size(); ++i)
      if (fine_columns[i] > 0 && !fixed[i])
        halo_blocks[i] = fine_columns[i] + degree[i] / 4;  // (integer division)
    return op.sum_over_nodes(halo_blocks) / blocks;
  }
};

ExplicitSolver::FineGuess ExplicitSolver::guess_fine_nodes() const {
  // From K's whole rows (on many ranks completed over them: SoilOperator's row_magnitude_sums,
  // flagged_neighbours), each node's Gershgorin bound and the counts are one process's, so the
  // ranks choose its fine nodes and step (docs/fem-soil.md §8).
  const std::int64_t n = op_->nodes();
  FineGuess g{*op_, fixed_, a1_, std::vector<double>(n, 0.0), 0.0, std::vector<char>(n, 1),
              {},   0.0};
  const std::vector<double> sums = op_->row_magnitude_sums();
  for (std::int64_t i = 0; i < n; ++i) {
    if (fixed_[i]) continue;
    for (std::int64_t r = 3 * i; r < 3 * i + 3; ++r)
      g.bound[i] = std::max(g.bound[i], sums[r] / mass_[i]);
  }
  g.scale = omega_max_ * omega_max_ / op_->max_over_nodes(g.bound);  // lambda_max / largest
  g.degree = op_->flagged_neighbours(std::vector<char>(n, 1));
  g.blocks = op_->sum_over_nodes(std::vector<double>(g.degree.begin(), g.degree.end()));
  // Never fine: fixed nodes, the truncation surface's (its springs and dashpots stay outside the
  // recurrence, which keeps K_p symmetric), and the matched layer's and their neighbours (the
  // layer's forces stay outside too).
  std::vector<char> layer(n, 0);
  for (std::int64_t i = 0; i < n; ++i) {
    if (fixed_[i] || boundary_of_[i] >= 0) g.may_be_fine[i] = 0;
    layer[i] = pml_ && pml_->layer_node(i) >= 0;
  }
  if (pml_) {
    const std::vector<std::int32_t> near_layer = op_->flagged_neighbours(layer);
    for (std::int64_t i = 0; i < n; ++i)
      if (near_layer[i] > 0) g.may_be_fine[i] = 0;
  }
  return g;
}

bool ExplicitSolver::local_step_feasible(double dt, int substeps) const {
  // Its stabilization exists, the fine nodes' spectrum fits the recurrence, and the matched
  // layer allows it.
  const double lambda_max = omega_max_ * omega_max_;
  const double tau = LocalTimeStepping::tau_for(dt, a1_);
  return tau > 0.0 && lambda_max <= 0.9 * LocalTimeStepping::fine_range(dt, tau, substeps) &&
         dt <= pml_step_;
}

std::vector<ExplicitSolver::LocalStepCandidate> ExplicitSolver::local_step_candidates(
    const FineGuess& guess, int substeps, double macro_step, double courant) const {
  std::vector<LocalStepCandidate> candidates;
  if (macro_step > 0.0) {
    // Work per macro step: n sub-steps, each a pass over K plus the extra sub-steps' share,
    // against one rate's count. Each n is tried with the usual guess of the fine nodes and with
    // a wider one (nodes above half their limit), which a step just above what the usual guess
    // verifies may need.
    const auto single_count = std::ceil(macro_step / (courant * single_rate_step_) - 1e-9);
    for (double count = single_count - 1.0; count >= 1.0; count -= 1.0) {
      const double dt = macro_step / (count * courant);  // (grows as count falls)
      if (dt < 1.1 * single_rate_step_) continue;
      if (!local_step_feasible(dt, substeps)) break;
      for (const double safety : {FineGuess::kSafety, 0.5}) {
        const double work =
            count * (1.0 + (substeps - 1) * guess.extra_work(guess.fine_at(dt, safety)));
        if (work < 0.95 * single_count) candidates.push_back({work, dt, safety});
      }
    }
  } else {  // work per simulated second, for steps from 1.1 to p times one rate's
    for (double ratio = 1.1; ratio <= substeps + 1e-9; ratio += 0.05) {
      const double dt = ratio * single_rate_step_;
      if (!local_step_feasible(dt, substeps)) break;
      const double work =
          (1.0 + (substeps - 1) * guess.extra_work(guess.fine_at(dt, FineGuess::kSafety))) / dt;
      if (work < 0.95 / single_rate_step_) candidates.push_back({work, dt, FineGuess::kSafety});
    }
  }
  std::sort(
      candidates.begin(), candidates.end(),
      [](const LocalStepCandidate& a, const LocalStepCandidate& b) { return a.work < b.work; });
  return candidates;
}

bool ExplicitSolver::verify_local_steps(const FineGuess& guess,
                                        const std::vector<LocalStepCandidate>& candidates,
                                        int substeps, double macro_step) {
  // Verify by the largest eigenvalue of M^-1 (K_p + S): the bound only guesses which nodes are
  // stiff. When a step fails by a little (a coarse node a little too stiff for it), the same fine
  // nodes are verified again at 97 % of the step the iteration allows (not for a macro step's
  // candidates, whose steps are exact: the next one is tried); else the next candidate.
  const int tries = macro_step > 0.0 ? 4 : 3;
  const std::int64_t n = op_->nodes();
  std::size_t next = 0;
  double dt = 0.0;
  std::vector<char> fine;
  // The recurrence integrates the fine nodes' fastest modes, which with the Maxwell mechanisms
  // see the unrelaxed stiffness: its polynomial is built on (1 + sum c_l) M^-1 K, by a mass
  // scaled down by that factor (M R(A P) M^-1 is unchanged otherwise).
  const Eigen::VectorXd recurrence_mass = op_->mass() / maxwell_.unrelaxed();
  for (int t = 0; t < tries; ++t) {
    if (dt == 0.0) {
      if (next == candidates.size()) break;
      dt = candidates[next].step;
      fine = guess.fine_at(dt, candidates[next].safety);
      ++next;
    }
    const std::vector<char> halo =
        LocalTimeStepping::halo_flags(fine, op_->fixed(), op_->flagged_neighbours(fine));
    lts_.emplace([this](const SoilOperator::BlockVisit& visit) { op_->for_each_step_block(visit); },
                 recurrence_mass, fine, halo, op_->fixed(), substeps);
    if (op_->spans_ranks())
      lts_->sum_over_ranks(op_->shared_nodes(), [op = op_.get()](double* values, int width) {
        op->sum_shared_nodes(values, width);
      });
    halo_of_.assign(n, -1);
    for (std::size_t h = 0; h < lts_->halo().size(); ++h)
      halo_of_[lts_->halo()[h]] = static_cast<std::int32_t>(h);
    halo_forces_.assign(3 * lts_->halo().size(), 0.0);
    local_step_ = dt;  // (prepare_local_steps' message)
    int iterations = 0;
    const double mu = largest_eigenvalue(
        [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) { effective_stiffness_times(x, y, dt); },
        iterations);
    eigen_iterations_ += iterations;
    const double allowed = step_limit(mu);
    if (dt <= allowed) return true;
    dt = macro_step == 0.0 && 0.97 * allowed > 1.05 * single_rate_step_ ? 0.97 * allowed : 0.0;
  }
  return false;
}

ExplicitSolver::LocalStepNodes ExplicitSolver::local_step_nodes() const {
  const std::int64_t n = op_->nodes();
  std::vector<double> fine(n, 0.0), halo(n, 0.0);
  if (lts_)
    for (std::size_t h = 0; h < lts_->halo().size(); ++h)
      (static_cast<std::int64_t>(h) < lts_->fine_nodes() ? fine : halo)[lts_->halo()[h]] = 1.0;
  const double fine_nodes = op_->sum_over_nodes(fine);
  return {fine_nodes, fine_nodes + op_->sum_over_nodes(halo),
          op_->sum_over_nodes(std::vector<double>(n, 1.0))};
}

void ExplicitSolver::drop_local_steps() {
  lts_.reset();
  halo_of_.clear();
  local_step_ = 0.0;
}

bool ExplicitSolver::enable_local_steps(int substeps, double macro_step, double courant) {
  drop_local_steps();
  last_step_local_ = false;
  // Steps up to courant x one rate's stable step are taken on one rate, within the caller's
  // margin; longer ones with the local steps, within the same margin of the verified step.
  one_rate_limit_ = courant * single_rate_step_;
  // From there up, the damping's lag must leave room for a stabilization (tau_for > 0), so that
  // every step between it and the verified one can be taken.
  // A matched layer whose own limit is below 1.1 times one rate's leaves nothing to gain.
  if (substeps < 2 || LocalTimeStepping::tau_for(one_rate_limit_, a1_) == 0.0 ||
      pml_step_ < 1.1 * single_rate_step_)
    return false;
  const FineGuess guess = guess_fine_nodes();
  const std::vector<LocalStepCandidate> candidates =
      local_step_candidates(guess, substeps, macro_step, courant);
  if (verify_local_steps(guess, candidates, substeps, macro_step)) return true;
  drop_local_steps();
  return false;
}

}  // namespace rumble::fem
