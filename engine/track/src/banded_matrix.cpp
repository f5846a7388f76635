#include "track/banded_matrix.hpp"

#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rumble {

BandedSymmetric::BandedSymmetric(std::size_t n, std::size_t half_bandwidth)
    : n_(n), b_(half_bandwidth), data_((half_bandwidth + 1) * n, 0.0) {}

void BandedSymmetric::set_zero() {
  std::fill(data_.begin(), data_.end(), 0.0);
}

void BandedSymmetric::add(std::size_t i, std::size_t j, double v) {
  if (i < j) std::swap(i, j);
  if (i - j > b_ || i >= n_) {
    throw std::logic_error("BandedSymmetric::add(" + std::to_string(i) + ", " + std::to_string(j) +
                           ") outside the band " + std::to_string(b_));
  }
  lower(i, j) += v;
}

double BandedSymmetric::at(std::size_t i, std::size_t j) const {
  if (i < j) std::swap(i, j);
  return i - j > b_ || i >= n_ ? 0.0 : lower(i, j);
}

void BandedSymmetric::set_combination(double a, const BandedSymmetric& x, double b,
                                      const BandedSymmetric& y, double c,
                                      const BandedSymmetric& z) {
  for (std::size_t k = 0; k < data_.size(); ++k)
    data_[k] = a * x.data_[k] + b * y.data_[k] + c * z.data_[k];
}

void BandedSymmetric::multiply(const double* x, double* y) const {
  std::fill(y, y + n_, 0.0);
  multiply_add(1.0, x, y);
}

void BandedSymmetric::multiply_add(double alpha, const double* x, double* y) const {
  for (std::size_t j = 0; j < n_; ++j) {
    const double* col = &data_[(b_ + 1) * j];
    double sum = col[0] * x[j];
    const std::size_t last = std::min(n_ - 1, j + b_);
    for (std::size_t i = j + 1; i <= last; ++i) {
      const double a = col[i - j];
      sum += a * x[i];           // row j, column i (upper part, by symmetry)
      y[i] += alpha * a * x[j];  // row i, column j
    }
    y[j] += alpha * sum;
  }
}

bool BandedSymmetric::factorize() {
  // LAPACK's band Cholesky: the same lower band storage, and as fast as the loop of our own it
  // replaced (bench/numerics/lapack_compare_bench: 0.98-1.02x at n = 6000, b = 4-24).
  const auto n = static_cast<lapack_int>(n_), b = static_cast<lapack_int>(b_);
  if (n_ > 0 && LAPACKE_dpbtrf_work(LAPACK_COL_MAJOR, 'L', n, b, data_.data(), b + 1) != 0)
    return false;
  // Reciprocals: the sweeps are latency-bound chains, and a division costs several times a
  // multiplication there.
  inverse_diagonal_.resize(n_);
  for (std::size_t j = 0; j < n_; ++j) inverse_diagonal_[j] = 1.0 / lower(j, j);
  return true;
}

void BandedSymmetric::solve(double* x) const {
  // Our own sweeps, not LAPACK's dpbtrs: this solve runs in every micro step, and ours is
  // 1.2-1.8x faster (bench/numerics/lapack_compare_bench, n = 1200-6000, b = 4-24: dpbtrs goes
  // through two BLAS triangular band solves). Column-oriented, so that both sweeps read the
  // stored columns contiguously.
  for (std::size_t j = 0; j < n_; ++j) {  // L y = rhs
    const double* col = &data_[(b_ + 1) * j];
    const double yj = x[j] * inverse_diagonal_[j];
    x[j] = yj;
    const std::size_t len = std::min(b_, n_ - 1 - j);
    for (std::size_t k = 1; k <= len; ++k) x[j + k] -= col[k] * yj;
  }
  for (std::size_t j = n_; j-- > 0;) {  // L^T x = y
    const double* col = &data_[(b_ + 1) * j];
    const std::size_t len = std::min(b_, n_ - 1 - j);
    double s = x[j];
    for (std::size_t k = 1; k <= len; ++k) s -= col[k] * x[j + k];
    x[j] = s * inverse_diagonal_[j];
  }
}

}  // namespace rumble
