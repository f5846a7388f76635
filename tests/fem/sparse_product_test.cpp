// Multigrid's threaded sparse products (sparse_product.hpp) against Eigen's, on random matrices
// with empty rows and columns, for one to three threads (more threads than rows included).
#include "operator/sparse_product.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

namespace rumble::fem {
namespace {

/// A rows x cols matrix with about `per_row` entries in each row, none in every fifth row.
RowSparse random_sparse(int rows, int cols, int per_row, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> column(0, cols - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> entries;
  for (int r = 0; r < rows; ++r)
    if (r % 5 != 4)
      for (int k = 0; k < per_row; ++k) entries.emplace_back(r, column(rng), value(rng));
  RowSparse m(rows, cols);
  m.setFromTriplets(entries.begin(), entries.end());  // (duplicates summed)
  return m;
}

void expect_equal_to_eigens(const RowSparse& a, const RowSparse& b, unsigned threads) {
  const RowSparse c = sparse_product(a, b, threads);
  const RowSparse expected = a * b;
  ASSERT_EQ(c.rows(), expected.rows());
  ASSERT_EQ(c.cols(), expected.cols());
  ASSERT_TRUE(c.isCompressed());
  // The same pattern (both keep every structural entry) and the same sums: each entry is a sum
  // of the same products, perhaps in another order, so equal to a few units in the last place
  // of the sum of the terms' magnitudes (at most 6 x 4 terms of magnitude <= 1 here: 5e-15).
  ASSERT_EQ(c.nonZeros(), expected.nonZeros());
  for (int r = 0; r < c.rows(); ++r) {
    ASSERT_EQ(c.outerIndexPtr()[r + 1], expected.outerIndexPtr()[r + 1]) << "row " << r;
    RowSparse::InnerIterator mine(c, r), theirs(expected, r);
    for (; mine && theirs; ++mine, ++theirs) {
      ASSERT_EQ(mine.col(), theirs.col()) << "row " << r;  // (sorted, as Eigen's are)
      EXPECT_NEAR(mine.value(), theirs.value(), 1e-14) << "row " << r << ", column " << mine.col();
    }
  }
}

TEST(SparseProduct, EqualsEigensProductForAnyNumberOfThreads) {
  const RowSparse a = random_sparse(200, 150, 6, 1);
  const RowSparse b = random_sparse(150, 90, 4, 2);
  for (const unsigned threads : {1u, 2u, 3u}) expect_equal_to_eigens(a, b, threads);
  expect_equal_to_eigens(random_sparse(2, 7, 3, 3), random_sparse(7, 5, 2, 4), 3);  // 3 > rows
}

TEST(SparseProduct, RefusesMismatchedOrUncompressedOperands) {
  const RowSparse a = random_sparse(10, 8, 3, 5);
  EXPECT_THROW(sparse_product(a, random_sparse(9, 4, 2, 6), 1), std::invalid_argument);
  RowSparse uncompressed = random_sparse(8, 4, 2, 7);
  uncompressed.insert(4, 3) = 1.0;  // (row 4 was empty: inserting leaves the matrix uncompressed)
  ASSERT_FALSE(uncompressed.isCompressed());
  EXPECT_THROW(sparse_product(a, uncompressed, 1), std::invalid_argument);
}

TEST(SparseProduct, MatrixTimesVectorEqualsEigensForAnyNumberOfThreads) {
  // Each entry is the same row's sum in the same order as Eigen's: equal to round-off (at most 6
  // terms of magnitude <= 1: 1e-15).
  const RowSparse a = random_sparse(200, 150, 6, 8);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(150, -1.0, 1.0);
  const Eigen::VectorXd expected = a * x;
  for (const unsigned threads : {1u, 2u, 3u}) {
    Eigen::VectorXd y;
    multiply(a, x, y, threads);
    EXPECT_LE((y - expected).cwiseAbs().maxCoeff(), 1e-15) << threads << " threads";
    Eigen::VectorXd z = Eigen::VectorXd::Ones(200);
    multiply_add(a, x, z, threads);
    EXPECT_LE((z - expected - Eigen::VectorXd::Ones(200)).cwiseAbs().maxCoeff(), 1e-15);
  }
  // With the values in float (multigrid's V-cycle): the product of the rounded matrix, in double.
  const RowSparseFloat rounded = a.cast<float>();
  const Eigen::VectorXd expected_rounded = rounded.cast<double>() * x;
  Eigen::VectorXd y;
  multiply(rounded, x, y, 2);
  EXPECT_LE((y - expected_rounded).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_GT((y - expected).cwiseAbs().maxCoeff(), 0.0);  // (it did read the rounded values)
  Eigen::VectorXd wrong_size = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(multiply_add(a, x, wrong_size, 1), std::invalid_argument);
}

}  // namespace
}  // namespace rumble::fem
