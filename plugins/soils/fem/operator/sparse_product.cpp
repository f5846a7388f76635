#include "operator/sparse_product.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rumble::fem {

RowSparse sparse_product(const RowSparse& a, const RowSparse& b, unsigned threads) {
  if (a.cols() != b.rows())
    throw std::invalid_argument("sparse_product: the inner dimensions differ");
  if (!a.isCompressed() || !b.isCompressed())
    throw std::invalid_argument("sparse_product: the operands must be compressed");
  const int rows = static_cast<int>(a.rows()), cols = static_cast<int>(b.cols());
  const int* a_start = a.outerIndexPtr();
  const int* a_column = a.innerIndexPtr();
  const double* a_value = a.valuePtr();
  const int* b_start = b.outerIndexPtr();
  const int* b_column = b.innerIndexPtr();
  const double* b_value = b.valuePtr();
  const int teams = static_cast<int>(std::max(1u, threads));
  constexpr int kRowsPerChunk = 256;  // (rows differ in work: shared out as they finish)

  // Two passes, the pattern's sizes and then the entries, so that the result is written once
  // in place: no growing buffers (pages first touched cost more than the arithmetic on a
  // virtual machine: bench/fem/MEASUREMENTS.md, "Speed and memory").
  RowSparse c(rows, cols);
  int* start = c.outerIndexPtr();
#pragma omp parallel num_threads(teams)
  {
    std::vector<int> last_row(static_cast<std::size_t>(cols), -1);  // the row that met column c
#pragma omp for schedule(dynamic, kRowsPerChunk)
    for (int r = 0; r < rows; ++r) {
      int count = 0;
      for (int p = a_start[r]; p < a_start[r + 1]; ++p) {
        const int j = a_column[p];
        for (int q = b_start[j]; q < b_start[j + 1]; ++q) {
          const auto k = static_cast<std::size_t>(b_column[q]);
          if (last_row[k] != r) {
            last_row[k] = r;
            ++count;
          }
        }
      }
      start[r + 1] = count;
    }
  }
  start[0] = 0;
  std::int64_t nonzeros = 0;
  for (int r = 0; r < rows; ++r) {
    nonzeros += start[r + 1];
    if (nonzeros > std::numeric_limits<int>::max())
      throw std::length_error("sparse_product: the product has too many nonzeros for int indices");
    start[r + 1] = static_cast<int>(nonzeros);
  }
  c.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
  int* column = c.innerIndexPtr();
  double* value = c.valuePtr();
#pragma omp parallel num_threads(teams)
  {
    std::vector<double> sum(static_cast<std::size_t>(cols));
    std::vector<int> last_row(static_cast<std::size_t>(cols), -1);
#pragma omp for schedule(dynamic, kRowsPerChunk)
    for (int r = 0; r < rows; ++r) {
      int* pattern = column + start[r];
      int count = 0;
      for (int p = a_start[r]; p < a_start[r + 1]; ++p) {
        const int j = a_column[p];
        const double a_rj = a_value[p];
        for (int q = b_start[j]; q < b_start[j + 1]; ++q) {
          const auto k = static_cast<std::size_t>(b_column[q]);
          if (last_row[k] != r) {
            last_row[k] = r;
            sum[k] = a_rj * b_value[q];
            pattern[count++] = b_column[q];
          } else {
            sum[k] += a_rj * b_value[q];
          }
        }
      }
      std::sort(pattern, pattern + count);
      for (int e = 0; e < count; ++e)
        value[start[r] + e] = sum[static_cast<std::size_t>(pattern[e])];
    }
  }
  return c;
}

namespace {

template <bool kAdd, class Matrix>
void row_products(const Matrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y, unsigned threads) {
  const std::int64_t rows = a.rows();
  const int* start = a.outerIndexPtr();
  const int* column = a.innerIndexPtr();
  const auto* value = a.valuePtr();
  const double* in = x.data();
  double* out = y.data();
#pragma omp parallel for num_threads(threads < 1 ? 1 : threads) schedule(static)
  for (std::int64_t r = 0; r < rows; ++r) {
    double sum = 0.0;
    for (int k = start[r]; k < start[r + 1]; ++k) sum += value[k] * in[column[k]];
    out[r] = kAdd ? out[r] + sum : sum;
  }
}

/// y = A x or y += A x, checked.
template <bool kAdd, class Matrix>
void checked_row_products(const Matrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                          unsigned threads) {
  if (!a.isCompressed() || x.size() != a.cols())
    throw std::invalid_argument("multiply: the matrix must be compressed and x its columns'");
  if (!kAdd) y.resize(a.rows());
  if (y.size() != a.rows()) throw std::invalid_argument("multiply_add: y must be the rows'");
  row_products<kAdd>(a, x, y, threads);
}

}  // namespace

void multiply(const RowSparse& a, const Eigen::VectorXd& x, Eigen::VectorXd& y, unsigned threads) {
  checked_row_products<false>(a, x, y, threads);
}
void multiply(const RowSparseFloat& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
              unsigned threads) {
  checked_row_products<false>(a, x, y, threads);
}
void multiply_add(const RowSparse& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                  unsigned threads) {
  checked_row_products<true>(a, x, y, threads);
}
void multiply_add(const RowSparseFloat& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                  unsigned threads) {
  checked_row_products<true>(a, x, y, threads);
}

}  // namespace rumble::fem
