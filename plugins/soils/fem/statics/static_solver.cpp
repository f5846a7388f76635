#include "statics/static_solver.hpp"

#include <chrono>
#include <stdexcept>

#include "operator/effective_matrix.hpp"

namespace rumble::fem {

struct StaticSolver::Factor {
  Eigen::CholmodSupernodalLLT<LongSparse, Eigen::Lower> llt;
};

StaticSolver::StaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
                           Eigen::Index factor_limit, CgPreconditioner preconditioner)
    : op_(op), nodes_(nodes), factor_limit_(factor_limit), preconditioner_(preconditioner) {}
StaticSolver::~StaticSolver() = default;

void StaticSolver::release() {
  factor_.reset();
  gamg_.reset();
  geometric_.reset();
}

std::size_t StaticSolver::bytes() const {
  std::size_t b = 0;
  if (factor_) b += factor_->llt.cholmod().memory_inuse;
  if (gamg_) b += gamg_->bytes();
  if (geometric_) b += geometric_->bytes();
  return b;
}

int StaticSolver::multigrid_levels() const {
  if (gamg_) return gamg_->levels();
  return geometric_ ? geometric_->levels() : 0;
}

const char* StaticSolver::method() const {
  if (factor_) return "CHOLMOD";
  return preconditioner_ == CgPreconditioner::kGamg ? "CG + GAMG (PETSc)"
                                                    : "CG + geometric multigrid (PETSc)";
}

Eigen::VectorXd StaticSolver::solve(const Eigen::VectorXd& f) {
  if (op_.dofs() <= factor_limit_) return factor_solve(f);
  return preconditioner_ == CgPreconditioner::kGamg ? gamg_solve(f) : geometric_solve(f);
}

Eigen::VectorXd StaticSolver::factor_solve(const Eigen::VectorXd& f) {
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

Eigen::VectorXd StaticSolver::gamg_solve(const Eigen::VectorXd& f) {
  if (!gamg_) {
    gamg_ = std::make_unique<PetscStaticSolver>(op_, nodes_);
    multigrid_seconds_ = gamg_->setup_seconds();
  }
  Eigen::VectorXd u = gamg_->solve(f);
  cg_iterations_ = gamg_->last_iterations();
  return u;
}

Eigen::VectorXd StaticSolver::geometric_solve(const Eigen::VectorXd& f) {
  if (!geometric_) {
    if (!coarse_level_)
      throw std::logic_error("fem: the geometric multigrid's statics without a coarse level");
    const auto start = std::chrono::steady_clock::now();
    geometric_ = std::make_unique<GeometricStaticSolver>(op_, coarse_level_);
    multigrid_seconds_ =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  Eigen::VectorXd u = geometric_->solve(f);
  cg_iterations_ = geometric_->last_iterations();
  return u;
}

}  // namespace rumble::fem
