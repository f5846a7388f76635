#include "statics/static_solver.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

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
  multigrid_.reset();
  gamg_.reset();
  geometric_.reset();
  Eigen::VectorXd().swap(diagonal_);
}

std::size_t StaticSolver::bytes() const {
  std::size_t b = static_cast<std::size_t>(diagonal_.size() + last_.size()) * 8;
  if (factor_) b += factor_->llt.cholmod().memory_inuse;
  if (multigrid_) b += multigrid_->bytes();
  if (geometric_) b += geometric_->bytes();
  return b;
}

int StaticSolver::multigrid_levels() const {
  if (gamg_) return gamg_->levels();
  if (geometric_) return geometric_->levels();
  return multigrid_ ? multigrid_->levels() : 0;
}

const char* StaticSolver::method() const {
  if (factor_) return "CHOLMOD";
  switch (preconditioner_) {
    case CgPreconditioner::kGamg:
      return "CG + GAMG (PETSc)";
    case CgPreconditioner::kGeometric:
      return "CG + geometric multigrid (PETSc)";
    case CgPreconditioner::kMultigrid:
      return "CG + multigrid";
    case CgPreconditioner::kJacobi:
      break;
  }
  return "CG + Jacobi";
}

Eigen::VectorXd StaticSolver::solve(const Eigen::VectorXd& f) {
  if (op_.dofs() > factor_limit_ && preconditioner_ == CgPreconditioner::kGamg) {
    if (!gamg_) {
      gamg_ = std::make_unique<PetscStaticSolver>(op_, nodes_);
      multigrid_seconds_ = gamg_->setup_seconds();
    }
    Eigen::VectorXd u = gamg_->solve(f);
    cg_iterations_ = gamg_->last_iterations();
    return u;
  }
  if (op_.dofs() > factor_limit_ && preconditioner_ == CgPreconditioner::kGeometric)
    return geometric_solve(f);
  if (op_.dofs() > factor_limit_) return conjugate_gradients(f);
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

void StaticSolver::build_multigrid() {
  const auto start = std::chrono::steady_clock::now();
  // K + S in K's own storage, handed over by the operator (which builds K again if a later call
  // needs it) rather than copied: at 1e6 DOFs 0.39 GB instead of K's 0.58 GB beside a copy.
  MeshMatrix A(op_.take_stiffness(), op_);
  multigrid_ = std::make_unique<AmgPreconditioner>(
      std::move(A), nodes_,
      [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
        op_.stepped_stiffness_times(x, y, true);
      },
      op_.threads());
  multigrid_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void StaticSolver::prepare_preconditioner(Eigen::Index n) {
  if (last_.size() != n) last_ = Eigen::VectorXd::Zero(n);
  if (preconditioner_ == CgPreconditioner::kMultigrid) {
    if (!multigrid_) build_multigrid();
    return;
  }
  if (diagonal_.size() == n) return;
  // Jacobi: the diagonal of K + S.
  const CsrMatrix& K = op_.stiffness();
  diagonal_ = Eigen::VectorXd::Zero(n);
  for (Eigen::Index r = 0; r < n; ++r)
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
      if (K.column()[k] == r) diagonal_[r] = K.value()[k];
  for (const BoundaryNode& b : op_.boundary())
    for (int c = 0; c < 3; ++c) diagonal_[3 * b.node + c] += b.spring(c, c);
}

Eigen::VectorXd StaticSolver::conjugate_gradients(const Eigen::VectorXd& f) {
  const Eigen::Index n = f.size();
  prepare_preconditioner(n);
  Eigen::VectorXd x = last_, r = f, z(n), p(n), q;
  for (Eigen::Index k = 0; k < n; ++k)
    if (op_.fixed()[k / 3]) r[k] = 0.0;
  const double target = 1e-10 * r.norm();
  if (target == 0.0) {  // no load on a free DOF: at rest
    cg_iterations_ = 0;
    last_.setZero();
    return last_;
  }
  // The products read K as the step does (its upper blocks, threaded, in the step's precision):
  // a sixth of the bytes of K's double rows, so the iteration streams mostly the V-cycle's. The
  // static state is then the one of the operator the dynamics step (K rounded to float, §4.2),
  // which the soil starts from at rest; the factor's path (smaller meshes) solves K in double.
  op_.stepped_stiffness_times(x, q, true);  // (zero on fixed DOFs, as x is)
  r -= q;
  precondition(r, z);
  p = z;
  double rz = r.dot(z);
  for (cg_iterations_ = 0; cg_iterations_ < 20000 && r.norm() > target; ++cg_iterations_) {
    op_.check_stop();  // (Ctrl-C: a solve at 1e6 DOFs takes several seconds)
    op_.stepped_stiffness_times(p, q, true);
    const double alpha = rz / p.dot(q);
    x += alpha * p;
    r -= alpha * q;
    precondition(r, z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  if (!(r.norm() <= target)) {
    std::ostringstream m;
    m << "fem: the static solve (conjugate gradients) did not converge in " << cg_iterations_
      << " iterations (residual " << r.norm() / f.norm() << " of the load)";
    throw std::runtime_error(m.str());
  }
  last_ = x;
  return x;
}

void StaticSolver::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (multigrid_)
    multigrid_->apply(r, z);
  else
    z = r.cwiseQuotient(diagonal_);
}

}  // namespace rumble::fem
