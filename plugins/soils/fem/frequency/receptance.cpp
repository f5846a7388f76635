#include "frequency/receptance.hpp"

// GCC 12's -Wnull-dereference false positive inside Eigen's sparse insert (static_solver.cpp).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/SparseCore>
#include <Eigen/UmfPackSupport>
#pragma GCC diagnostic pop
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::fem {

namespace {

// 64-bit indices select UMFPACK's umfpack_zl_* routines. With int indices (umfpack_zi_*) the
// factorization failed on the paper study's medium soil at 50 Hz (1.6e5 DOFs) with 17 GB free:
// the int version's sizes and pointers are 32-bit.
using ComplexSparse = Eigen::SparseMatrix<std::complex<double>, Eigen::ColMajor, SuiteSparse_long>;

std::string umfpack_status(SuiteSparse_long status) {
  switch (status) {
    case UMFPACK_WARNING_singular_matrix:
      return "singular matrix";
    case UMFPACK_ERROR_out_of_memory:
      return "out of memory";
    default:
      return "UMFPACK status " + std::to_string(status);
  }
}

}  // namespace

struct Receptance::Lu {
  ComplexSparse A;
  Eigen::UmfPackLU<ComplexSparse> lu;
  Eigen::MatrixXcd rhs;  // B: ndof x n
  bool analysed = false;
};

Receptance::Receptance(const ExplicitSolver& op, const FootprintWeights& weights, double a0,
                       double a1)
    : op_(op), weights_(weights), a0_(a0), a1_(a1), lu_(std::make_unique<Lu>()) {
  // The pattern of K (symmetric: its rows are its columns), values filled per frequency.
  const CsrMatrix& K = op_.stiffness();
  const std::int64_t n = K.rows();
  std::vector<int> count(n);
  for (std::int64_t c = 0; c < n; ++c)
    count[c] = static_cast<int>(K.row_start()[c + 1] - K.row_start()[c]);
  lu_->A.resize(n, n);
  lu_->A.reserve(count);
  for (std::int64_t c = 0; c < n; ++c)
    for (std::int64_t k = K.row_start()[c]; k < K.row_start()[c + 1]; ++k)
      lu_->A.insert(static_cast<SuiteSparse_long>(K.column()[k]), c) = 0.0;
  lu_->A.makeCompressed();
  lu_->rhs = Eigen::MatrixXcd::Zero(n, static_cast<Eigen::Index>(weights_.size()));
  for (std::size_t j = 0; j < weights_.size(); ++j)
    for (const NodalWeight& w : weights_[j])
      lu_->rhs(3 * w.node + 2, static_cast<Eigen::Index>(j)) = w.weight;
}

Receptance::~Receptance() = default;

void Receptance::assemble_soil(double w) {
  const std::complex<double> i_w(0.0, w);
  const CsrMatrix& K = op_.stiffness();
  const auto& fixed = op_.fixed();
  ComplexSparse& A = lu_->A;
  // A = K (1 + i w a1) + diag(m (i w a0 - w^2)) + S + i w D, fixed DOFs as identity rows/columns;
  // with the Maxwell mechanisms K's factor is their complex modulus (a0 = a1 = 0).
  const std::complex<double> stiffness_factor = op_.maxwell_damping().modulus(w) + i_w * a1_;
  const std::int64_t n = K.rows();
  for (std::int64_t c = 0; c < n; ++c) {
    std::complex<double>* value = A.valuePtr() + A.outerIndexPtr()[c];
    const SuiteSparse_long* row = A.innerIndexPtr() + A.outerIndexPtr()[c];
    const std::int64_t count = A.outerIndexPtr()[c + 1] - A.outerIndexPtr()[c];
    for (std::int64_t k = 0; k < count; ++k) {
      const std::int64_t r = row[k];
      if (fixed[r / 3] || fixed[c / 3]) {
        value[k] = r == c ? 1.0 : 0.0;
        continue;
      }
      value[k] = K.value()[K.row_start()[c] + k] * stiffness_factor;
      if (r == c) value[k] += op_.mass()[c / 3] * (i_w * a0_ - w * w);
    }
  }
}

void Receptance::add_layer(double w) {
  const auto& fixed = op_.fixed();
  ComplexSparse& A = lu_->A;
  // The matched layer's stretched-minus-elastic stiffness and its mass side (pml.hpp), in the
  // pattern of K (the layer's tetrahedra are the mesh's).
  if (const PmlLayer* layer = op_.pml())
    layer->frequency_domain(
        w,
        [&](std::int32_t a, std::int32_t b, const Eigen::Matrix3cd& block) {
          if (fixed[a] || fixed[b]) return;
          for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) A.coeffRef(3 * a + j, 3 * b + c) += block(j, c);
        },
        [&](std::int32_t node, std::complex<double> value) {
          if (fixed[node]) return;
          for (int c = 0; c < 3; ++c) A.coeffRef(3 * node + c, 3 * node + c) += value;
        });
}

void Receptance::add_boundary(double w) {
  const std::complex<double> i_w(0.0, w);
  const auto& fixed = op_.fixed();
  ComplexSparse& A = lu_->A;
  const bool springs = op_.springs_act();
  for (const BoundaryNode& b : op_.boundary()) {
    if (fixed[b.node]) continue;
    for (int d = 0; d < 3; ++d) {
      double unit[3] = {0.0, 0.0, 0.0}, spring[3] = {0.0, 0.0, 0.0}, dashpot[3] = {0.0, 0.0, 0.0};
      unit[d] = 1.0;
      if (springs) b.apply_spring(unit, spring);
      b.apply_dashpot(unit, dashpot);
      for (int c = 0; c < 3; ++c)
        A.coeffRef(3 * b.node + c, 3 * b.node + d) += spring[c] + i_w * dashpot[c];
    }
  }
}

void Receptance::factorize(double f_hz) {
  ComplexSparse& A = lu_->A;
  if (!lu_->analysed) {
    // The matrix is complex symmetric with a symmetric pattern: UMFPACK's symmetric strategy
    // (diagonal pivots preferred) with a METIS ordering fills far less than the default.
    lu_->lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
    lu_->lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
    // One solve per footprint: UMFPACK's default two steps of iterative refinement would triple
    // the solves' cost (they are most of the time) for digits the receptance does not need.
    lu_->lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
    lu_->lu.analyzePattern(A);
    lu_->analysed = true;
  }
  lu_->lu.factorize(A);
  if (lu_->lu.info() != Eigen::Success)
    throw std::runtime_error(
        "fem: the receptance's LU failed at " + std::to_string(f_hz) +
        " Hz (UMFPACK: " + umfpack_status(lu_->lu.umfpackFactorizeReturncode()) + ", " +
        std::to_string(op_.stiffness().rows()) + " DOFs)");
}

void Receptance::at(double f_hz, std::complex<double>* H) {
  const double w = 2.0 * std::numbers::pi * f_hz;
  assemble_soil(w);
  add_layer(w);
  add_boundary(w);
  factorize(f_hz);
  Eigen::MatrixXcd x;
  if (far_ != nullptr && lag_ != nullptr) {
    Eigen::MatrixXcd rhs = lu_->rhs;
    far_->add_columns(lag_->at(w), rhs);
    x = lu_->lu.solve(rhs);
  } else {
    x = lu_->lu.solve(lu_->rhs);
  }
  // H: the footprints' weighted vertical displacement under each footprint's unit load.
  const Eigen::Index m = lu_->rhs.cols();
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = 0; i < m; ++i) {
      std::complex<double> s = 0.0;
      for (const NodalWeight& nw : weights_[static_cast<std::size_t>(i)])
        s += nw.weight * x(3 * nw.node + 2, j);
      H[j * m + i] = s;
    }
}

}  // namespace rumble::fem
