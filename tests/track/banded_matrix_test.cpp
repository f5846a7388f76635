// The banded Cholesky against a dense solve of the same matrix (Eigen LLT): a second method.
#include "track/banded_matrix.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace rumble {
namespace {

TEST(BandedSymmetric, SolveMatchesDenseCholesky) {
  const std::size_t n = 40, b = 4;
  BandedSymmetric a(n, b);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = (i > b ? i - b : 0); j < i; ++j) {
      const double v = u(rng);
      a.add(i, j, v);
      dense(Eigen::Index(i), Eigen::Index(j)) += v;
      dense(Eigen::Index(j), Eigen::Index(i)) += v;
    }
    a.add(i, i, 10.0);  // diagonally dominant: positive definite
    dense(Eigen::Index(i), Eigen::Index(i)) += 10.0;
  }
  Eigen::VectorXd x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) x[Eigen::Index(i)] = u(rng);
  a.multiply(x.data(), y.data());
  EXPECT_LT((y - dense * x).norm(), 1e-12 * y.norm());  // product uses both triangles
  ASSERT_TRUE(a.factorize());
  Eigen::VectorXd sol = y;
  a.solve(sol.data());
  // Condition number ~ 2 for this matrix: round-off far below 1e-12.
  EXPECT_LT((sol - x).norm(), 1e-12 * x.norm());
}

TEST(BandedSymmetric, ReportsIndefiniteMatrix) {
  BandedSymmetric a(3, 1);
  a.add(0, 0, 1.0);
  a.add(1, 1, -1.0);
  a.add(2, 2, 1.0);
  EXPECT_FALSE(a.factorize());
}

}  // namespace
}  // namespace rumble
