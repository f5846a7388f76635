#include "static_solver.hpp"

// GCC 12 reports a null dereference inside Eigen's SparseCompressedBase when insert() is inlined
// (a false positive: the matrix is reserved first); the pragma must cover the header itself.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#pragma GCC diagnostic pop
#include <SuiteSparse_config.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rumble::fem {

using LongSparse = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

struct StaticSolver::Factor {
  Eigen::CholmodSupernodalLLT<LongSparse, Eigen::Lower> llt;
};

StaticSolver::StaticSolver(const ExplicitSolver& op) : op_(op) {}
StaticSolver::~StaticSolver() = default;

namespace {

/// The lower triangle of K + S as CSC (K's rows are its columns: it is symmetric), fixed DOFs
/// replaced by identity rows and columns.
LongSparse lower_static_matrix(const ExplicitSolver& op) {
  const CsrMatrix& K = op.stiffness();
  const std::int64_t n = K.rows();
  std::vector<double> spring_block(9 * op.mass().size(), 0.0);
  for (const BoundaryNode& b : op.boundary())
    for (int d = 0; d < 3; ++d) {
      double unit[3] = {0.0, 0.0, 0.0};
      unit[d] = 1.0;
      double column[3] = {0.0, 0.0, 0.0};
      BoundaryNode::apply(b.normal, b.spring_normal, b.spring_tangential, unit, column);
      for (int c = 0; c < 3; ++c) spring_block[9 * b.node + 3 * c + d] = column[c];
    }
  LongSparse A(n, n);
  std::vector<SuiteSparse_long> count(n, 0);
  for (std::int64_t col = 0; col < n; ++col)
    for (std::int64_t k = K.row_start()[col]; k < K.row_start()[col + 1]; ++k)
      if (K.column()[k] >= col) ++count[col];
  A.reserve(count);
  const auto& fixed = op.fixed();
  for (std::int64_t col = 0; col < n; ++col) {
    const std::int64_t node = col / 3;
    if (fixed[node]) {
      A.insert(col, col) = 1.0;
      continue;
    }
    for (std::int64_t k = K.row_start()[col]; k < K.row_start()[col + 1]; ++k) {
      const std::int64_t row = K.column()[k];
      if (row < col || fixed[row / 3]) continue;
      double value = K.value()[k];
      if (row / 3 == node) value += spring_block[9 * node + 3 * (row % 3) + col % 3];
      A.insert(row, col) = value;
    }
  }
  A.makeCompressed();
  return A;
}

}  // namespace

Eigen::VectorXd StaticSolver::solve(const Eigen::VectorXd& f) {
  if (op_.dofs() > kFactorLimit) return conjugate_gradients(f);
  if (!factor_) {
    factor_ = std::make_unique<Factor>();
    factor_->llt.compute(lower_static_matrix(op_));
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

Eigen::VectorXd StaticSolver::conjugate_gradients(const Eigen::VectorXd& f) {
  // Jacobi preconditioner: the diagonal of K + S.
  const CsrMatrix& K = op_.stiffness();
  const Eigen::Index n = f.size();
  Eigen::VectorXd diagonal(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    diagonal[r] = 0.0;
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
      if (K.column()[k] == r) diagonal[r] = K.value()[k];
  }
  for (const BoundaryNode& b : op_.boundary())
    for (int c = 0; c < 3; ++c)
      diagonal[3 * b.node + c] +=
          b.spring_tangential + (b.spring_normal - b.spring_tangential) * b.normal[c] * b.normal[c];
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), r = f, z(n), p(n), q;
  for (Eigen::Index k = 0; k < n; ++k)
    if (op_.fixed()[k / 3]) r[k] = 0.0;
  const double target = 1e-10 * r.norm();
  z = r.cwiseQuotient(diagonal);
  p = z;
  double rz = r.dot(z);
  for (cg_iterations_ = 0; cg_iterations_ < 20000 && r.norm() > target; ++cg_iterations_) {
    op_.stiffness_times(p, q, true);
    const double alpha = rz / p.dot(q);
    x += alpha * p;
    r -= alpha * q;
    z = r.cwiseQuotient(diagonal);
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
  return x;
}

}  // namespace rumble::fem
