// LU factorisation with partial pivoting of a symmetric tridiagonal matrix, real or complex
// (the algorithm of LAPACK's ?gttrf/?gtts2, written for one scalar type T). The reduced soils'
// matrices are tridiagonal: factoring costs O(n), one solve O(n), so the exact n x n receptance
// costs O(n^2) instead of the O(n^3) of a dense LU. Pivoting keeps it exact near the resonances
// of the complex dynamic stiffness K - w^2 M + i w C, whose real part is indefinite there.
// Storage is sized once by resize(); factor() and solve() never allocate.
// Ours rather than LAPACK's ?gttrf/?gttrs (bench/numerics/lapack_compare_bench, factor + solve,
// n = 100-7000): real, in every step of the reduced soils, ours is 1.2-1.3x faster; complex, once
// per frequency for the receptance, LAPACK's is 1.25-1.3x faster, a few microseconds per solve.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>

namespace rumble::soils {

template <class T>
class TridiagonalLu {
 public:
  using Vector = Eigen::Matrix<T, Eigen::Dynamic, 1>;

  void resize(Eigen::Index n) {
    n_ = n;
    d_.resize(n);
    dl_.resize(std::max<Eigen::Index>(n - 1, 0));
    du_.resize(std::max<Eigen::Index>(n - 1, 0));
    du2_.resize(std::max<Eigen::Index>(n - 2, 0));
    swapped_.resize(std::max<Eigen::Index>(n - 1, 0));
  }

  /// Factors the matrix with diagonal `diag` (n) and equal sub- and super-diagonal `off` (n - 1).
  /// Returns false when a pivot is exactly zero (the matrix is singular).
  bool factor(const Vector& diag, const Vector& off) {
    d_ = diag;
    dl_ = off;
    du_ = off;
    for (Eigen::Index i = 0; i + 1 < n_; ++i) {
      swapped_[i] = std::abs(d_[i]) < std::abs(dl_[i]);
      if (!swapped_[i]) {
        if (d_[i] == T(0)) return false;
        const T l = dl_[i] / d_[i];
        dl_[i] = l;
        d_[i + 1] -= l * du_[i];
        if (i + 2 < n_) du2_[i] = T(0);
      } else {  // rows i and i + 1 exchanged: a second super-diagonal appears
        const T l = d_[i] / dl_[i];
        d_[i] = dl_[i];
        dl_[i] = l;
        const T upper = du_[i];
        du_[i] = d_[i + 1];
        d_[i + 1] = upper - l * d_[i + 1];
        if (i + 2 < n_) {
          du2_[i] = du_[i + 1];
          du_[i + 1] = -l * du_[i + 1];
        }
      }
    }
    if (n_ > 0 && d_[n_ - 1] == T(0)) return false;
    d_ = d_.cwiseInverse();  // solve() multiplies: a complex division costs ~10 products
    return true;
  }

  /// Overwrites b with the solution x of A x = b; b[i] = 0 for i < first (a saving for unit
  /// right-hand sides: the forward sweep starts there).
  void solve(Vector& b, Eigen::Index first = 0) const {
    for (Eigen::Index i = std::max<Eigen::Index>(first - 1, 0); i + 1 < n_; ++i) {
      if (!swapped_[i]) {
        b[i + 1] -= dl_[i] * b[i];
      } else {
        const T t = b[i];
        b[i] = b[i + 1];
        b[i + 1] = t - dl_[i] * b[i];
      }
    }
    if (n_ == 0) return;
    b[n_ - 1] *= d_[n_ - 1];
    if (n_ > 1) b[n_ - 2] = (b[n_ - 2] - du_[n_ - 2] * b[n_ - 1]) * d_[n_ - 2];
    for (Eigen::Index i = n_ - 3; i >= 0; --i)
      b[i] = (b[i] - du_[i] * b[i + 1] - du2_[i] * b[i + 2]) * d_[i];
  }

  Eigen::Index size() const { return n_; }

 private:
  Eigen::Index n_ = 0;
  Vector d_, dl_, du_, du2_;  // 1 / U's diagonal, U's upper diagonals, L's multipliers (?gttrf)
  Eigen::Matrix<bool, Eigen::Dynamic, 1> swapped_;
};

}  // namespace rumble::soils
