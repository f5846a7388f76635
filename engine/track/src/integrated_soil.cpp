#include "track/integrated_soil.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "track/bandwidth_order.hpp"

namespace rumble {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// Largest |entry|; 0 for an empty matrix. (Iterated, not coeffs(): that needs a compressed
/// matrix, which a caller's need not be.)
double largest_abs(const Sparse& a) {
  double m = 0.0;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (Sparse::InnerIterator it(a, j); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

/// Largest |A - A^T| relative to the largest |A|; 0 for an empty matrix.
double asymmetry(const Sparse& a) {
  const double scale = largest_abs(a);
  if (scale == 0.0) return 0.0;
  const Sparse transposed = a.transpose();
  return largest_abs(Sparse(a - transposed)) / scale;
}

BandedSymmetric banded(const Sparse& a, std::size_t band) {
  BandedSymmetric out(static_cast<std::size_t>(a.rows()), band);
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (Sparse::InnerIterator it(a, j); it; ++it)
      if (it.row() >= it.col())  // the lower triangle; add() mirrors it
        out.add(static_cast<std::size_t>(it.row()), static_cast<std::size_t>(it.col()), it.value());
  return out;
}

}  // namespace

IntegratedSoil::IntegratedSoil(const std::string& name, const Sparse& M, const Sparse& C,
                               const Sparse& K, const Sparse& B, double max_band_storage)
    : n_x_(static_cast<std::size_t>(K.rows())), n_f_(static_cast<std::size_t>(B.cols())) {
  const auto refuse = [&](const std::string& what) {
    return RunError("soil '" + name +
                    "' cannot be integrated with the track (monolithic): " + what);
  };
  for (const auto& [m, label] : {std::pair{&M, "M"}, std::pair{&C, "C"}, std::pair{&K, "K"}}) {
    if (static_cast<std::size_t>(m->rows()) != n_x_ || static_cast<std::size_t>(m->cols()) != n_x_)
      throw refuse(std::string(label) + " is " + std::to_string(m->rows()) + " x " +
                   std::to_string(m->cols()) + ", K is " + std::to_string(n_x_) + " x " +
                   std::to_string(n_x_));
    // Round-off of an assembled matrix is ~1e-16 relative; 1e-10 leaves room for any sum order.
    if (const double d = asymmetry(*m); d > 1e-10) {
      std::ostringstream text;
      text << label << " is not symmetric (largest |" << label << " - " << label << "^T| is " << d
           << " of its largest entry)";
      throw refuse(text.str());
    }
  }
  if (static_cast<std::size_t>(B.rows()) != n_x_)
    throw refuse("B has " + std::to_string(B.rows()) + " rows, K has " + std::to_string(n_x_));
  // The soil's own order, or reverse Cuthill-McKee where that narrows the band (a mesh's nodes
  // come in any order); the matrices are then held permuted, which only the band sees.
  const Sparse pattern = Sparse(M.cwiseAbs()) + Sparse(C.cwiseAbs()) + Sparse(K.cwiseAbs());
  band_ = rumble::half_bandwidth(pattern);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, Sparse::StorageIndex> order(
      static_cast<Eigen::Index>(n_x_));
  order.setIdentity();
  if (band_ > 1) {
    const std::vector<Eigen::Index> rcm = bandwidth_reducing_order(pattern);
    if (const std::size_t narrower = rumble::half_bandwidth(pattern, rcm); narrower < band_) {
      band_ = narrower;
      for (std::size_t k = 0; k < rcm.size(); ++k)
        order.indices()[rcm[k]] = static_cast<Sparse::StorageIndex>(k);  // unknown rcm[k] -> k
    }
  }
  sparse_ = static_cast<double>(band_ + 1) * static_cast<double>(n_x_) > max_band_storage;
  if (sparse_ && static_cast<double>(n_x_) > kMaxSparseDofs) {
    std::ostringstream text;
    text << n_x_ << " DOFs with a half bandwidth of " << band_
         << " are too many to factor at every micro-step (at most " << kMaxSparseDofs
         << " held sparse); use a smaller soil (or a co-simulation scheme: gauss_seidel, "
            "implicit)";
    throw refuse(text.str());
  }
  if (sparse_) {  // the soil's own order: the factorization chooses its fill-reducing one
    sparse_mass_ = M;
    sparse_damping_ = C;
    sparse_stiffness_ = K;
    for (Sparse* m : {&sparse_mass_, &sparse_damping_, &sparse_stiffness_}) m->makeCompressed();
    input_ = B;
    input_.makeCompressed();
    sparse_static_.compute(sparse_stiffness_);
    if (sparse_static_.info() != Eigen::Success)
      throw refuse("its stiffness K is not positive definite (a soil with no static stiffness)");
    sparse_dynamic_.analyzePattern(
        Sparse(sparse_stiffness_ + sparse_damping_ + sparse_mass_));  // A's pattern
    solved_.setZero(static_cast<Eigen::Index>(n_x_));
  } else {
    mass_ = banded(Sparse(order * M * order.transpose()), band_);
    damping_ = banded(Sparse(order * C * order.transpose()), band_);
    stiffness_ = banded(Sparse(order * K * order.transpose()), band_);
    input_ = order * B;
    input_.makeCompressed();
    static_factor_ = stiffness_;
    if (!static_factor_.factorize())
      throw refuse("its stiffness K is not positive definite (a soil with no static stiffness)");
    dynamic_ = BandedSymmetric(n_x_, band_);
  }
  G_.setZero(static_cast<Eigen::Index>(n_f_), static_cast<Eigen::Index>(n_f_));
  for (Eigen::VectorXd* v : {&x_, &v_, &a_, &pa_, &pv_, &rhs_, &free_, &x_old_})
    v->setZero(static_cast<Eigen::Index>(n_x_));
  offset_.setZero(static_cast<Eigen::Index>(n_f_));
}

void IntegratedSoil::solve_static(Eigen::VectorXd& x) const {
  if (!sparse_) {
    static_factor_.solve(x.data());
    return;
  }
  solved_ = sparse_static_.solve(x);
  x.swap(solved_);
}

void IntegratedSoil::solve_dynamic(Eigen::VectorXd& x) const {
  if (!sparse_) {
    dynamic_.solve(x.data());
    return;
  }
  solved_ = sparse_dynamic_.solve(x);
  x.swap(solved_);
}

void IntegratedSoil::inertia_and_damping(const Eigen::VectorXd& a, const Eigen::VectorXd& v,
                                         Eigen::VectorXd& y) const {
  if (!sparse_) {
    mass_.multiply(a.data(), y.data());
    damping_.multiply_add(1.0, v.data(), y.data());
    return;
  }
  y.noalias() = sparse_mass_ * a;
  y.noalias() += sparse_damping_ * v;
}

double IntegratedSoil::footprint_dot(std::size_t i, const Eigen::VectorXd& x) const {
  double s = 0.0;
  for (Sparse::InnerIterator it(input_, static_cast<Eigen::Index>(i)); it; ++it)
    s += it.value() * x[it.row()];
  return s;
}

void IntegratedSoil::add_input(const double* force, Eigen::VectorXd& y) const {
  for (std::size_t i = 0; i < n_f_; ++i)
    for (Sparse::InnerIterator it(input_, static_cast<Eigen::Index>(i)); it; ++it)
      y[it.row()] += it.value() * force[i];
}

void IntegratedSoil::static_displacement(const double* force, double* u) {
  rhs_.setZero();
  add_input(force, rhs_);
  solve_static(rhs_);
  for (std::size_t i = 0; i < n_f_; ++i) u[i] = footprint_dot(i, rhs_);
}

void IntegratedSoil::start_static(const double* force, const double* held) {
  x_.setZero();
  add_input(force, x_);
  solve_static(x_);
  v_.setZero();
  a_.setZero();
  offset_.setZero();
  if (held != nullptr)
    for (std::size_t i = 0; i < n_f_; ++i)
      offset_[static_cast<Eigen::Index>(i)] = held[i] - footprint_dot(i, x_);
}

void IntegratedSoil::factorize(const Newmark& newmark, double h) {
  if (h == h_factored_) return;
  bool factored = false;
  if (sparse_) {
    sparse_dynamic_.factorize(Sparse(sparse_stiffness_ + newmark.c_v(h) * sparse_damping_ +
                                     newmark.c_a(h) * sparse_mass_));
    factored = sparse_dynamic_.info() == Eigen::Success;
  } else {
    dynamic_.set_combination(1.0, stiffness_, newmark.c_v(h), damping_, newmark.c_a(h), mass_);
    factored = dynamic_.factorize();
  }
  if (!factored) {
    throw RunError(
        "integrated soil: K + c_v C + c_a M is not positive definite at the micro-step " +
        std::to_string(h) + " s");
  }
  Eigen::VectorXd column(static_cast<Eigen::Index>(n_x_));
  for (std::size_t j = 0; j < n_f_; ++j) {
    column.setZero();
    for (Sparse::InnerIterator it(input_, static_cast<Eigen::Index>(j)); it; ++it)
      column[it.row()] = it.value();
    solve_dynamic(column);
    for (std::size_t i = 0; i < n_f_; ++i)
      G_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = footprint_dot(i, column);
  }
  G_ = 0.5 * (G_ + G_.transpose()).eval();  // symmetric to round-off; made exactly so
  h_factored_ = h;
}

void IntegratedSoil::predict(const Newmark& newmark, double h, Eigen::VectorXd& u0,
                             Eigen::VectorXd& p) {
  newmark.predictors(h, x_, v_, a_, pa_, pv_);
  inertia_and_damping(pa_, pv_, rhs_);
  free_ = rhs_;
  solve_dynamic(free_);
  for (std::size_t i = 0; i < n_f_; ++i) {
    u0[static_cast<Eigen::Index>(i)] = footprint_dot(i, free_);
    p[static_cast<Eigen::Index>(i)] = footprint_dot(i, pv_);
  }
}

void IntegratedSoil::correct(const Newmark& newmark, double h, const Eigen::VectorXd& force) {
  x_old_ = x_;
  x_ = rhs_;
  add_input(force.data(), x_);
  solve_dynamic(x_);
  newmark.correct(h, x_old_, x_, v_, a_);
}

double IntegratedSoil::footprint_u(std::size_t i) const {
  return footprint_dot(i, x_) + offset_[static_cast<Eigen::Index>(i)];
}

double IntegratedSoil::footprint_v(std::size_t i) const {
  return footprint_dot(i, v_);
}

double* IntegratedSoil::save_state(double* b) const {
  for (const Eigen::VectorXd* v : {&x_, &v_, &a_})
    b = std::copy(v->data(), v->data() + v->size(), b);
  return b;
}

const double* IntegratedSoil::restore_state(const double* b) {
  for (Eigen::VectorXd* v : {&x_, &v_, &a_}) {
    std::copy(b, b + v->size(), v->data());
    b += v->size();
  }
  return b;
}

}  // namespace rumble
