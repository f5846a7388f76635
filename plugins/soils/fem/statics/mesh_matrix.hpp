// Multigrid's matrix on the mesh (amg_preconditioner.hpp): K + S with the held DOFs as identity
// rows and columns, the entries full_combination(op, {.stiffness = 1, .springs = true}) gives
// (effective_matrix.hpp), in the same order and to the bit, but kept in K's own 3 x 3 blocks by
// node (CsrMatrix::release_blocks): no column index per value, so 8 B per nonzero instead of
// Eigen's 12, and no copy of K at all where the operator hands its K over (take_stiffness,
// soil_operator.hpp). At 1e6 DOFs that is 0.39 GB instead of 0.55 GB beside K's 0.58 GB
// (docs/fem-soil.md section 7.2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "operator/csr_matrix.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class MeshMatrix {
 public:
  /// K (the operator's, handed over or copied) turned into K + S in place; op: its boundary
  /// blocks and held nodes.
  MeshMatrix(CsrMatrix K, const SoilOperator& op);

  std::int64_t nodes() const { return static_cast<std::int64_t>(held_.size()); }
  std::int64_t rows() const { return 3 * nodes(); }
  /// The entries for_each_in_row visits, all rows together.
  std::int64_t nonzeros() const { return nonzeros_; }
  bool held(std::int64_t node) const { return held_[static_cast<std::size_t>(node)] != 0; }
  std::int64_t degree(std::int64_t node) const {
    return b_.neighbour_start[node + 1] - b_.neighbour_start[node];
  }
  /// The node's neighbours in K's graph (sorted, itself included), held ones too.
  const std::int32_t* neighbours(std::int64_t node) const {
    return b_.neighbour.data() + b_.neighbour_start[node];
  }
  /// visit(column, value) for each entry of `row`, columns ascending: a held row has its
  /// diagonal 1 alone, and held columns are left out.
  template <class Visit>
  void for_each_in_row(std::int64_t row, Visit&& visit) const {
    const std::int64_t i = row / 3;
    if (held(i)) {
      visit(row, 1.0);
      return;
    }
    const std::int64_t deg = degree(i);
    const double* value = b_.value.data() + 9 * b_.neighbour_start[i] + 3 * (row % 3) * deg;
    const std::int32_t* nb = neighbours(i);
    for (std::int64_t p = 0; p < deg; ++p) {
      if (held(nb[p])) continue;
      for (int d = 0; d < 3; ++d) visit(3 * static_cast<std::int64_t>(nb[p]) + d, value[3 * p + d]);
    }
  }
  double diagonal(std::int64_t row) const;
  std::size_t bytes() const {
    return b_.neighbour_start.size() * 8 + b_.neighbour.size() * 4 + b_.value.size() * 8 +
           held_.size();
  }

 private:
  CsrMatrix::Blocks b_;
  std::vector<char> held_;
  std::int64_t nonzeros_ = 0;
};

}  // namespace rumble::fem
