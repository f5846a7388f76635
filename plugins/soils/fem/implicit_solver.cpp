#include "implicit_solver.hpp"

#include <sstream>
#include <stdexcept>

#include "effective_matrix.hpp"

namespace rumble::fem {

namespace {
constexpr double kBeta = 0.25, kGamma = 0.5;
}

struct ImplicitSolver::Factor {
  Eigen::CholmodSupernodalLLT<LongSparse, Eigen::Lower> llt;
};

ImplicitSolver::ImplicitSolver(const ExplicitSolver& op, double a0, double a1)
    : op_(op), a0_(a0), a1_(a1), factor_(std::make_unique<Factor>()) {}

ImplicitSolver::~ImplicitSolver() = default;

void ImplicitSolver::step(ExplicitState& s, const Eigen::VectorXd& f, double dt) {
  const double c0 = 1.0 / (kBeta * dt * dt), c1 = kGamma / (kBeta * dt), c2 = 1.0 / (kBeta * dt);
  const double c3 = 0.5 / kBeta - 1.0, c4 = kGamma / kBeta - 1.0;
  const double c5 = 0.5 * dt * (kGamma / kBeta - 2.0);
  if (dt != factored_dt_) {
    factor_->llt.compute(lower_combination(op_, {.stiffness = 1.0 + c1 * a1_,
                                                 .mass = c0 + c1 * a0_,
                                                 .springs = op_.springs_act(),
                                                 .dashpots = c1}));
    if (factor_->llt.info() != Eigen::Success) {
      std::ostringstream m;
      m << "fem: the implicit step's matrix could not be factored at dt = " << dt
        << " s (CHOLMOD: out of memory, or not positive definite); use the explicit scheme";
      throw std::runtime_error(m.str());
    }
    factored_dt_ = dt;
    ++factorizations_;
  }
  const Eigen::Index n = s.w.size();
  y_ = c1 * s.w + c4 * s.v + c5 * s.a;  // C acts on this
  z_ = c0 * s.w + c2 * s.v + c3 * s.a;  // M acts on this
  op_.stiffness_times(y_, ky_, false);
  rhs_.resize(n);
  const Eigen::VectorXd& m = op_.mass();
  for (Eigen::Index k = 0; k < n; ++k)
    rhs_[k] = f[k] + m[k / 3] * (z_[k] + a0_ * y_[k]) + a1_ * ky_[k];
  for (const BoundaryNode& b : op_.boundary())
    BoundaryNode::apply(b.normal, b.dashpot_normal, b.dashpot_tangential, y_.data() + 3 * b.node,
                        rhs_.data() + 3 * b.node);
  for (Eigen::Index k = 0; k < n; ++k)
    if (op_.fixed()[k / 3]) rhs_[k] = 0.0;
  const Eigen::VectorXd w_new = factor_->llt.solve(rhs_);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double a_new = c0 * (w_new[k] - s.w[k]) - c2 * s.v[k] - c3 * s.a[k];
    s.v[k] += dt * ((1.0 - kGamma) * s.a[k] + kGamma * a_new);
    s.a[k] = a_new;
    s.w[k] = w_new[k];
  }
}

}  // namespace rumble::fem
