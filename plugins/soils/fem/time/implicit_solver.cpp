#include "time/implicit_solver.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "operator/effective_matrix.hpp"

namespace rumble::fem {

namespace {

constexpr double kBeta = 0.25, kGamma = 0.5;

class CholmodSystem final : public EffectiveSystem {
 public:
  explicit CholmodSystem(const SoilOperator& soil) : soil_(soil) {}
  void build(const Combination& c, double dt) override {
    llt_.compute(lower_combination(soil_, c));
    if (llt_.info() == Eigen::Success) return;
    std::ostringstream m;
    m << "fem: the implicit step's matrix could not be factored at dt = " << dt
      << " s (CHOLMOD: out of memory, or not positive definite); use the explicit scheme";
    throw std::runtime_error(m.str());
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& r) override { return llt_.solve(r); }

 private:
  const SoilOperator& soil_;
  Eigen::CholmodSupernodalLLT<LongSparse, Eigen::Lower> llt_;
};

}  // namespace

std::unique_ptr<EffectiveSystem> cholmod_system(const SoilOperator& soil) {
  return std::make_unique<CholmodSystem>(soil);
}

ImplicitSolver::ImplicitSolver(const ExplicitSolver& op, double a0, double a1,
                               std::unique_ptr<EffectiveSystem> system)
    : op_(op), a0_(a0), a1_(a1), system_(system ? std::move(system) : cholmod_system(op.soil())) {}

ImplicitSolver::~ImplicitSolver() = default;

void ImplicitSolver::step(ExplicitState& s, const Eigen::VectorXd& f, double dt) {
  const double c0 = 1.0 / (kBeta * dt * dt), c1 = kGamma / (kBeta * dt), c2 = 1.0 / (kBeta * dt);
  const double c3 = 0.5 / kBeta - 1.0, c4 = kGamma / kBeta - 1.0;
  const double c5 = 0.5 * dt * (kGamma / kBeta - 2.0);
  // The Maxwell mechanisms at the new displacement, z_l' = e_l z_l + g_l (w' - w) (exact for w
  // linear over the step, as in the explicit step), put (1 + sum c_l g_l) K on w' and
  // K h, h = sum c_l (e_l z_l - g_l w), on the right.
  const MaxwellDamping& maxwell = op_.maxwell_damping();
  const int mechanisms = maxwell.mechanisms();
  const Eigen::Index n = s.w.size();
  if (mechanisms > 0 && s.maxwell.size() != mechanisms * n)
    s.maxwell = Eigen::VectorXf::Zero(mechanisms * n);
  std::array<double, MaxwellDamping::kMaxMechanisms> decay{}, gain{};
  double memory_stiffness = 0.0;  // sum c_l g_l
  for (int l = 0; l < mechanisms; ++l) {
    const double rate_dt = maxwell.rates[l] * dt;
    decay[l] = std::exp(-rate_dt);
    gain[l] = -std::expm1(-rate_dt) / rate_dt;
    memory_stiffness += maxwell.weights[l] * gain[l];
  }
  if (dt != factored_dt_) {
    system_->build({.stiffness = 1.0 + c1 * a1_ + memory_stiffness,
                    .mass = c0 + c1 * a0_,
                    .springs = op_.springs_act(),
                    .dashpots = c1},
                   dt);
    factored_dt_ = dt;
    ++factorizations_;
  }
  y_ = c1 * s.w + c4 * s.v + c5 * s.a;  // C acts on this
  z_ = c0 * s.w + c2 * s.v + c3 * s.a;  // M acts on this
  // K acts on a1 y - h.
  q_ = a1_ * y_;
  for (Eigen::Index k = 0; k < n && mechanisms > 0; ++k)
    for (int l = 0; l < mechanisms; ++l)
      q_[k] -= maxwell.weights[l] * (decay[l] * s.maxwell[mechanisms * k + l] - gain[l] * s.w[k]);
  op_.stiffness_times(q_, ky_, false);
  rhs_.resize(n);
  const Eigen::VectorXd& m = op_.mass();
  for (Eigen::Index k = 0; k < n; ++k) rhs_[k] = f[k] + m[k / 3] * (z_[k] + a0_ * y_[k]) + ky_[k];
  for (const BoundaryNode& b : op_.boundary())
    BoundaryNode::apply(b.normal, b.dashpot_normal, b.dashpot_tangential, y_.data() + 3 * b.node,
                        rhs_.data() + 3 * b.node);
  for (Eigen::Index k = 0; k < n; ++k)
    if (op_.fixed()[k / 3]) rhs_[k] = 0.0;
  const Eigen::VectorXd w_new = system_->solve(rhs_);
  for (Eigen::Index k = 0; k < n; ++k) {
    for (int l = 0; l < mechanisms; ++l) {
      float& z = s.maxwell[mechanisms * k + l];
      z = static_cast<float>(decay[l] * z + gain[l] * (w_new[k] - s.w[k]));
    }
    const double a_new = c0 * (w_new[k] - s.w[k]) - c2 * s.v[k] - c3 * s.a[k];
    s.v[k] += dt * ((1.0 - kGamma) * s.a[k] + kGamma * a_new);
    s.a[k] = a_new;
    s.w[k] = w_new[k];
  }
}

}  // namespace rumble::fem
