#include "effective_matrix.hpp"

#include <vector>

namespace rumble::fem {

LongSparse lower_combination(const ExplicitSolver& op, const Combination& c) {
  const CsrMatrix& K = op.stiffness();
  const std::int64_t n = K.rows();
  // The boundary blocks per node, row-major 3 x 3: c.springs S + c.dashpots D.
  std::vector<double> block(9 * op.mass().size(), 0.0);
  for (const BoundaryNode& b : op.boundary())
    for (int d = 0; d < 3; ++d) {
      double unit[3] = {0.0, 0.0, 0.0}, column[3] = {0.0, 0.0, 0.0};
      unit[d] = 1.0;
      if (c.springs)
        BoundaryNode::apply(b.normal, b.spring_normal, b.spring_tangential, unit, column);
      BoundaryNode::apply(b.normal, c.dashpots * b.dashpot_normal,
                          c.dashpots * b.dashpot_tangential, unit, column);
      for (int r = 0; r < 3; ++r) block[9 * b.node + 3 * r + d] += column[r];
    }
  LongSparse A(n, n);
  std::vector<SuiteSparse_long> count(n, 0);
  for (std::int64_t col = 0; col < n; ++col)
    for (std::int64_t k = K.row_start()[col]; k < K.row_start()[col + 1]; ++k)
      if (K.column()[k] >= col) ++count[col];
  A.reserve(count);
  const auto& fixed = op.fixed();
  // K is symmetric: its row `col` is its column `col`.
  for (std::int64_t col = 0; col < n; ++col) {
    const std::int64_t node = col / 3;
    if (fixed[node]) {
      A.insert(col, col) = 1.0;
      continue;
    }
    for (std::int64_t k = K.row_start()[col]; k < K.row_start()[col + 1]; ++k) {
      const std::int64_t row = K.column()[k];
      if (row < col || fixed[row / 3]) continue;
      double value = c.stiffness * K.value()[k];
      if (row / 3 == node) value += block[9 * node + 3 * (row % 3) + col % 3];
      if (row == col) value += c.mass * op.mass()[node];
      A.insert(row, col) = value;
    }
  }
  A.makeCompressed();
  return A;
}

}  // namespace rumble::fem
