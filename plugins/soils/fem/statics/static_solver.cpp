#include "statics/static_solver.hpp"

#include <stdexcept>

#include "operator/effective_matrix.hpp"

namespace rumble::fem {

struct StaticSolver::Factor {
  Eigen::CholmodSupernodalLLT<LongSparse, Eigen::Lower> llt;
};

StaticSolver::StaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
                           Eigen::Index factor_limit)
    : op_(op), nodes_(nodes), factor_limit_(factor_limit) {}
StaticSolver::~StaticSolver() = default;

const char* StaticSolver::method() const {
  return op_.dofs() > factor_limit_ ? "CG + GAMG (PETSc)" : "CHOLMOD";
}

Eigen::VectorXd StaticSolver::solve(const Eigen::VectorXd& f) {
  if (op_.dofs() > factor_limit_) {
    if (!gamg_) gamg_ = std::make_unique<PetscStaticSolver>(op_, nodes_);
    return gamg_->solve(f);
  }
  if (!factor_) {
    factor_ = std::make_unique<Factor>();
    factor_->llt.compute(lower_combination(op_, {.stiffness = 1.0, .springs = true}));
    if (factor_->llt.info() != Eigen::Success) {
      factor_.reset();
      throw std::runtime_error(
          "fem: the static stiffness is not positive definite (CHOLMOD); the mesh floats: give "
          "the boundary springs (boundary.type viscous_spring or dashpot, alpha_normal > 0) or a "
          "fixed boundary");
    }
  }
  Eigen::VectorXd rhs = f;
  for (Eigen::Index k = 0; k < rhs.size(); ++k)
    if (op_.fixed()[k / 3]) rhs[k] = 0.0;
  Eigen::VectorXd u = factor_->llt.solve(rhs);
  if (factor_->llt.info() != Eigen::Success || !u.allFinite())
    throw std::runtime_error("fem: the static solve failed (CHOLMOD)");
  return u;
}

}  // namespace rumble::fem
