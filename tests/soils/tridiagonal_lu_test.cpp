// The tridiagonal LU behind time stepping and receptance, against Eigen's dense LU.
#include "tridiagonal_lu.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <complex>

namespace rumble::soils {
namespace {

template <class T>
Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> dense(
    const Eigen::Matrix<T, Eigen::Dynamic, 1>& d, const Eigen::Matrix<T, Eigen::Dynamic, 1>& o) {
  const auto n = d.size();
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> a =
      Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  a.diagonal() = d;
  for (Eigen::Index i = 0; i + 1 < n; ++i) a(i, i + 1) = a(i + 1, i) = o[i];
  return a;
}

template <class T>
double solve_error(const Eigen::Matrix<T, Eigen::Dynamic, 1>& d,
                   const Eigen::Matrix<T, Eigen::Dynamic, 1>& o) {
  TridiagonalLu<T> lu;
  lu.resize(d.size());
  EXPECT_TRUE(lu.factor(d, o));
  const Eigen::Matrix<T, Eigen::Dynamic, 1> b =
      Eigen::Matrix<T, Eigen::Dynamic, 1>::Random(d.size());
  Eigen::Matrix<T, Eigen::Dynamic, 1> x = b;
  lu.solve(x);
  const Eigen::Matrix<T, Eigen::Dynamic, 1> reference = dense(d, o).partialPivLu().solve(b);
  return (x - reference).norm() / reference.norm();
}

TEST(SoilTridiagonalLu, SolvesIndefiniteComplexSymmetricSystemsWithPivoting) {
  // Small diagonal entries force row exchanges (a dynamic stiffness near its resonances).
  Eigen::VectorXcd d = Eigen::VectorXcd::Random(40) * 0.1, o = Eigen::VectorXcd::Random(39);
  d[0] = 0.0;  // no LU without pivoting
  // Condition numbers of such random matrices stay below ~1e6: 1e-9 is round-off.
  EXPECT_LT(solve_error(d, o), 1e-9);
}

TEST(SoilTridiagonalLu, SolvesPositiveDefiniteRealSystems) {
  const Eigen::VectorXd d =
      Eigen::VectorXd::Constant(50, 4.0) + Eigen::VectorXd::Random(50).cwiseAbs();
  const Eigen::VectorXd o = Eigen::VectorXd::Random(49);
  EXPECT_LT(solve_error(d, o), 1e-14);
  for (const Eigen::Index n : {1, 2, 3}) {  // the smallest sizes use the special cases
    EXPECT_LT(solve_error(Eigen::VectorXd(d.head(n)), Eigen::VectorXd(o.head(n - 1))), 1e-14);
  }
}

TEST(SoilTridiagonalLu, ReportsASingularMatrix) {
  TridiagonalLu<double> lu;
  lu.resize(3);
  // [1 1 0; 1 1 0; 0 0 1] is singular.
  EXPECT_FALSE(lu.factor(Eigen::Vector3d(1, 1, 1), Eigen::Vector2d(1, 0)));
}

}  // namespace
}  // namespace rumble::soils
