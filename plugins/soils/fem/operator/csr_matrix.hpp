// A symmetric sparse matrix over the 3 DOFs per node of a mesh (DOF 3 i + c, c = x, y, z), in
// compressed rows: 8 B values + 4 B column indices per nonzero, the layout the explicit step
// streams once per sub-step (docs/numerics.md §5: memory-bound at 12 B/nnz). Row 3 i + c holds the
// 3 x deg(i) entries of node i's neighbours j (sorted, i included), columns 3 j + d.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

class CsrMatrix {
 public:
  /// The pattern of the mesh's node graph (zeros).
  explicit CsrMatrix(const TetMesh& mesh);

  std::int64_t rows() const { return static_cast<std::int64_t>(row_start_.size()) - 1; }
  std::int64_t nonzeros() const { return row_start_.back(); }
  /// The 3 x 3 block (node i, node j) as 3 pointers to its rows (each 3 contiguous values).
  /// j must be a neighbour of i (they share a tetrahedron), else std::out_of_range.
  double* block_row(std::int32_t i, std::int32_t j, int c);
  /// The diagonal's entries, one per row.
  std::vector<double> diagonal() const;
  /// Each block (i, j >= i) once, in ascending order: visit(i, j, values), K_ij's 9 values
  /// row-major (for a symmetric K, K_ji is its transpose).
  template <class Visit>
  void for_each_upper_block(Visit&& visit) const {
    double block[9];
    for (std::int32_t i = 0; i + 1 < static_cast<std::int32_t>(neighbour_start_.size()); ++i)
      for (std::int64_t q = 0; q < degree(i); ++q) {
        if (neighbours(i)[q] < i) continue;
        for (int e = 0; e < 9; ++e) block[e] = block_entry(i, q, e / 3, e % 3);
        visit(i, neighbours(i)[q], static_cast<const double*>(block));
      }
  }
  /// Per row, the sum of its entries' magnitudes (Gershgorin's bound on the eigenvalues).
  std::vector<double> magnitude_sums() const;
  /// Per node i, how many of its neighbours j (i itself included) have flag[j] set (flag: per
  /// node).
  std::vector<std::int32_t> flagged_neighbours(const std::vector<char>& flag) const;
  /// y = A x over rows [begin, end); x, y of size rows().
  void multiply_rows(const double* x, double* y, std::int64_t begin, std::int64_t end) const;
  /// Row r's product with x.
  double row_dot(std::int64_t r, const double* x) const {
    double s = 0.0;
    for (std::int64_t k = row_start_[r]; k < row_start_[r + 1]; ++k) s += value_[k] * x[column_[k]];
    return s;
  }

  /// Node i's three rows times x: out[c] = row 3 i + c . x. Reads one index per 3 x 3 block
  /// (the node graph's) instead of one per value: 4 B per 9 nonzeros, not 36, which is a quarter
  /// of the memory traffic of a product (docs/numerics.md §5: 12 B/nnz becomes 8.4).
  void node_rows_dot(std::int32_t i, const double* x, double out[3]) const {
    const std::int64_t first = neighbour_start_[i], deg = neighbour_start_[i + 1] - first;
    const double* r0 = value_.data() + 9 * first;  // row 3 i (layout: the constructor's)
    const double* r1 = r0 + 3 * deg;
    const double* r2 = r1 + 3 * deg;
    const std::int32_t* node = neighbour_.data() + first;
    // Two partial sums per row (even and odd blocks): twice the independent additions in flight,
    // 4-13 % faster on this machine (fem_bench, 1 and 2 threads).
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, t0 = 0.0, t1 = 0.0, t2 = 0.0;
    std::int64_t p = 0;
    for (; p + 1 < deg; p += 2) {
      const double* xj = x + 3 * static_cast<std::int64_t>(node[p]);
      const double* xk = x + 3 * static_cast<std::int64_t>(node[p + 1]);
      const std::int64_t t = 3 * p;
      s0 += r0[t] * xj[0] + r0[t + 1] * xj[1] + r0[t + 2] * xj[2];
      s1 += r1[t] * xj[0] + r1[t + 1] * xj[1] + r1[t + 2] * xj[2];
      s2 += r2[t] * xj[0] + r2[t + 1] * xj[1] + r2[t + 2] * xj[2];
      t0 += r0[t + 3] * xk[0] + r0[t + 4] * xk[1] + r0[t + 5] * xk[2];
      t1 += r1[t + 3] * xk[0] + r1[t + 4] * xk[1] + r1[t + 5] * xk[2];
      t2 += r2[t + 3] * xk[0] + r2[t + 4] * xk[1] + r2[t + 5] * xk[2];
    }
    if (p < deg) {
      const double* xj = x + 3 * static_cast<std::int64_t>(node[p]);
      const std::int64_t t = 3 * p;
      s0 += r0[t] * xj[0] + r0[t + 1] * xj[1] + r0[t + 2] * xj[2];
      s1 += r1[t] * xj[0] + r1[t + 1] * xj[1] + r1[t + 2] * xj[2];
      s2 += r2[t] * xj[0] + r2[t + 1] * xj[1] + r2[t + 2] * xj[2];
    }
    out[0] = s0 + t0;
    out[1] = s1 + t1;
    out[2] = s2 + t2;
  }

  /// Node i's neighbours (sorted, i included) and its block with the p-th of them: entry
  /// (3 i + c, 3 neighbours(i)[p] + d).
  std::int64_t degree(std::int32_t i) const {
    return neighbour_start_[i + 1] - neighbour_start_[i];
  }
  const std::int32_t* neighbours(std::int32_t i) const {
    return neighbour_.data() + neighbour_start_[i];
  }
  double block_entry(std::int32_t i, std::int64_t p, int c, int d) const {
    return value_[9 * neighbour_start_[i] + 3 * (c * degree(i) + p) + d];
  }

  const std::vector<std::int64_t>& row_start() const { return row_start_; }
  const std::vector<std::int32_t>& column() const { return column_; }
  const std::vector<double>& value() const { return value_; }
  std::size_t bytes() const {
    return row_start_.size() * 8 + column_.size() * 4 + value_.size() * 8 +
           neighbour_start_.size() * 8 + neighbour_.size() * 4;
  }

  /// The compressed rows alone (row starts, a column index per value, the values).
  struct Rows {
    std::vector<std::int64_t> start;  // rows + 1
    std::vector<std::int32_t> column;
    std::vector<double> value;
  };
  /// Hands over the rows and frees the node graph, the matrix left empty: for a reader of K by
  /// compressed rows that would otherwise copy them (PETSc's AIJ for GAMG,
  /// statics/petsc_static_solver.hpp).
  Rows release_rows() &&;

 private:
  std::vector<std::int64_t> neighbour_start_;  // node graph (node i: its sorted neighbours)
  std::vector<std::int32_t> neighbour_;
  std::vector<std::int64_t> row_start_;  // rows() + 1
  std::vector<std::int32_t> column_;
  std::vector<double> value_;
};

}  // namespace rumble::fem
