#include "operator/effective_matrix.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rumble::fem {

namespace {

/// Visits the combination's entries row by row, each row's columns ascending:
/// visit(row, column, value). A fixed DOF's row and column hold only its diagonal 1.
template <class Visit>
void for_each_entry(const SoilOperator& op, const Combination& c, Visit visit) {
  const CsrMatrix& K = op.stiffness();
  const std::vector<double> block = boundary_blocks(op, c);
  const auto& fixed = op.fixed();
  for (std::int64_t row = 0; row < K.rows(); ++row) {
    const std::int64_t node = row / 3;
    if (fixed[node]) {
      visit(row, row, 1.0);
      continue;
    }
    for (std::int64_t k = K.row_start()[row]; k < K.row_start()[row + 1]; ++k) {
      const std::int64_t col = K.column()[k];
      if (fixed[col / 3]) continue;
      double value = c.stiffness * K.value()[k];
      if (col / 3 == node) value += block[9 * node + 3 * (row % 3) + col % 3];
      if (row == col) value += c.mass * op.mass()[node];
      visit(row, col, value);
    }
  }
}

}  // namespace

void boundary_block(const BoundaryNode& b, const Combination& c, double out[9]) {
  std::fill_n(out, 9, 0.0);
  for (int d = 0; d < 3; ++d) {
    double unit[3] = {0.0, 0.0, 0.0}, column[3] = {0.0, 0.0, 0.0};
    unit[d] = 1.0;
    if (c.springs) b.apply_spring(unit, column);
    b.apply_dashpot(unit, column, c.dashpots);
    for (int r = 0; r < 3; ++r) out[3 * r + d] = column[r];
  }
  for (int r = 0; r < 3; ++r)
    for (int d = r + 1; d < 3; ++d) out[3 * r + d] = out[3 * d + r];
}

std::vector<double> boundary_blocks(const SoilOperator& op, const Combination& c) {
  std::vector<double> block(9 * op.mass().size(), 0.0);
  for (const BoundaryNode& b : op.boundary()) boundary_block(b, c, block.data() + 9 * b.node);
  return block;
}

LongSparse lower_combination(const SoilOperator& op, const Combination& c) {
  const CsrMatrix& K = op.stiffness();
  const std::int64_t n = K.rows();
  // The combination is symmetric: row `row`'s entries right of the diagonal are column `row`'s
  // below it, in order.
  std::vector<SuiteSparse_long> count(n, 0);
  for (std::int64_t r = 0; r < n; ++r)
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
      if (K.column()[k] >= r) ++count[r];
  LongSparse A(n, n);
  A.reserve(count);
  for_each_entry(op, c, [&](std::int64_t row, std::int64_t col, double value) {
    if (col >= row) A.insert(col, row) = value;
  });
  A.makeCompressed();
  return A;
}

RowSparse full_combination(const SoilOperator& op, const Combination& c) {
  const CsrMatrix& K = op.stiffness();
  if (K.nonzeros() > std::numeric_limits<int>::max())
    throw std::length_error("fem: the stiffness has too many nonzeros for 32-bit indices");
  const auto n = static_cast<int>(K.rows());
  RowSparse A(n, n);
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  for_each_entry(op, c, [&](std::int64_t row, std::int64_t, double) { ++count[row]; });
  A.reserve(count);
  for_each_entry(op, c, [&](std::int64_t row, std::int64_t col, double value) {
    A.insert(static_cast<int>(row), static_cast<int>(col)) = value;
  });
  A.makeCompressed();
  return A;
}

}  // namespace rumble::fem
