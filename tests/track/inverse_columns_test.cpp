// The cache of columns of A^-1 against the matrix itself: A times a cached column is the unit
// vector (a second method: the product, not the factor), through hits, evictions and clear().
#include "track/inverse_columns.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace rumble {
namespace {

constexpr std::size_t kN = 30, kBand = 3;

BandedSymmetric random_spd(BandedSymmetric* factor) {
  BandedSymmetric a(kN, kBand);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < kN; ++i) {
    for (std::size_t j = (i > kBand ? i - kBand : 0); j < i; ++j) a.add(i, j, u(rng));
    a.add(i, i, 8.0);  // diagonally dominant: positive definite, condition number ~ 2
  }
  *factor = a;
  EXPECT_TRUE(factor->factorize());
  return a;
}

/// max |A c - e_dof|: round-off (~1e-15) when c is column `dof` of A^-1.
double unit_residual(const BandedSymmetric& a, const double* c, std::size_t dof) {
  Eigen::VectorXd y(kN);
  a.multiply(c, y.data());
  y[static_cast<Eigen::Index>(dof)] -= 1.0;
  return y.cwiseAbs().maxCoeff();
}

TEST(InverseColumns, CachedColumnsAreColumnsOfTheInverseThroughEvictions) {
  BandedSymmetric factor;
  const BandedSymmetric a = random_spd(&factor);
  InverseColumns cache;
  cache.resize(kN, 4);
  for (std::size_t dof : {0u, 5u, 6u, 7u})
    EXPECT_LT(unit_residual(a, cache.column(dof, factor), dof), 1e-14);
  EXPECT_EQ(cache.solves(), 4u);
  // Hits: no new solve, same answer.
  for (std::size_t dof : {5u, 6u, 7u})
    EXPECT_LT(unit_residual(a, cache.column(dof, factor), dof), 1e-14);
  EXPECT_EQ(cache.solves(), 4u);
  // A fifth DOF evicts the least recently used (0), which then has to be solved again.
  EXPECT_LT(unit_residual(a, cache.column(29, factor), 29), 1e-14);
  EXPECT_EQ(cache.solves(), 5u);
  EXPECT_LT(unit_residual(a, cache.column(5, factor), 5), 1e-14);
  EXPECT_EQ(cache.solves(), 5u);
  EXPECT_LT(unit_residual(a, cache.column(0, factor), 0), 1e-14);
  EXPECT_EQ(cache.solves(), 6u);
}

TEST(InverseColumns, ClearForgetsColumnsOfTheOldMatrix) {
  BandedSymmetric factor;
  BandedSymmetric a = random_spd(&factor);
  InverseColumns cache;
  cache.resize(kN, 8);
  cache.column(3, factor);
  // A new matrix (as after a new micro-step size): 2 A, whose inverse is half the old one.
  BandedSymmetric doubled = a, doubled_factor;
  doubled.set_combination(2.0, a, 0.0, a, 0.0, a);
  doubled_factor = doubled;
  ASSERT_TRUE(doubled_factor.factorize());
  cache.clear();
  EXPECT_LT(unit_residual(doubled, cache.column(3, doubled_factor), 3), 1e-14);
  EXPECT_EQ(cache.solves(), 2u);
}

}  // namespace
}  // namespace rumble
