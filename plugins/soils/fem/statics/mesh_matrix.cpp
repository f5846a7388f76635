#include "statics/mesh_matrix.hpp"

#include <algorithm>
#include <utility>

#include "operator/effective_matrix.hpp"

namespace rumble::fem {

MeshMatrix::MeshMatrix(CsrMatrix K, const SoilOperator& op)
    : b_(std::move(K).release_blocks()), held_(op.fixed()) {
  // full_combination adds the boundary's block (zero off the truncation surface) to every
  // diagonal block, and 0 x M to the diagonal: the same additions here, so that even the sign of
  // a zero is the same.
  const std::vector<double> block = boundary_blocks(op, {.stiffness = 1.0, .springs = true});
  for (std::int64_t i = 0; i < nodes(); ++i) {
    if (held(i)) {
      nonzeros_ += 3;  // (its rows' diagonal 1s)
      continue;
    }
    const std::int64_t deg = degree(i);
    const std::int32_t* nb = neighbours(i);
    const auto self = std::lower_bound(nb, nb + deg, static_cast<std::int32_t>(i)) - nb;
    for (int c = 0; c < 3; ++c) {
      double* row = b_.value.data() + 9 * b_.neighbour_start[i] + 3 * c * deg;
      for (int d = 0; d < 3; ++d) row[3 * self + d] += block[9 * i + 3 * c + d];
      row[3 * self + c] += 0.0 * op.mass()[i];
    }
    for (std::int64_t p = 0; p < deg; ++p) nonzeros_ += held(nb[p]) ? 0 : 9;
  }
}

double MeshMatrix::diagonal(std::int64_t row) const {
  const std::int64_t i = row / 3;
  if (held(i)) return 1.0;
  const std::int64_t deg = degree(i);
  const std::int32_t* nb = neighbours(i);
  const auto self = std::lower_bound(nb, nb + deg, static_cast<std::int32_t>(i)) - nb;
  return b_.value[9 * b_.neighbour_start[i] + 3 * (row % 3) * deg + 3 * self + row % 3];
}

}  // namespace rumble::fem
