// Symmetric banded matrix with an in-place Cholesky factorization, for the track: with DOFs
// numbered along the rail (w_i, theta_i, then the sleeper under node i) every coupling is
// within 4 positions, so factor and solve cost O(n b^2) and O(n b) with no fill outside the
// band and no allocation after construction.
#pragma once

#include <cstddef>
#include <vector>

namespace rumble {

class BandedSymmetric {
 public:
  BandedSymmetric() = default;
  BandedSymmetric(std::size_t n, std::size_t half_bandwidth);

  std::size_t size() const { return n_; }
  std::size_t half_bandwidth() const { return b_; }
  void set_zero();
  /// Adds v to entries (i, j) and (j, i); |i - j| must be <= half_bandwidth.
  void add(std::size_t i, std::size_t j, double v);
  double at(std::size_t i, std::size_t j) const;
  /// this = a * x + b * y + c * z, all of the same shape.
  void set_combination(double a, const BandedSymmetric& x, double b, const BandedSymmetric& y,
                       double c, const BandedSymmetric& z);
  /// y = A x (y must have size n; no aliasing).
  void multiply(const double* x, double* y) const;
  /// y += alpha A x.
  void multiply_add(double alpha, const double* x, double* y) const;

  /// Cholesky factorization in place (A = L L^T). Returns false when A is not positive definite.
  bool factorize();
  /// Solves A x = rhs in place after factorize().
  void solve(double* rhs) const;

 private:
  double& lower(std::size_t i, std::size_t j) { return data_[(i - j) + (b_ + 1) * j]; }
  double lower(std::size_t i, std::size_t j) const { return data_[(i - j) + (b_ + 1) * j]; }
  std::size_t n_ = 0;
  std::size_t b_ = 0;
  std::vector<double> data_;              // column j holds A(j..j+b, j)
  std::vector<double> inverse_diagonal_;  // 1 / L(j, j) after factorize()
};

}  // namespace rumble
