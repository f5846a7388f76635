#include "operator/linear_matrices.hpp"

// GCC 12's -Wnull-dereference false positive inside Eigen's sparse insert (static_solver.cpp).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/SparseCore>
#pragma GCC diagnostic pop
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::fem {
namespace {

using Triplets = std::vector<Eigen::Triplet<double, std::int64_t>>;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

/// factor x K (the elastic stiffness) without the rows and columns of fixed nodes.
void add_stiffness(const SoilOperator& op, double factor, Triplets& t) {
  const CsrMatrix& K = op.stiffness();
  const auto& fixed = op.fixed();
  for (std::int64_t r = 0; r < K.rows(); ++r) {
    if (fixed[static_cast<std::size_t>(r / 3)]) continue;
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k) {
      const std::int64_t c = K.column()[k];
      if (!fixed[static_cast<std::size_t>(c / 3)]) t.emplace_back(r, c, factor * K.value()[k]);
    }
  }
}

/// factor x the lumped mass.
void add_mass(const SoilOperator& op, double factor, Triplets& t) {
  for (Eigen::Index node = 0; node < op.mass().size(); ++node) {
    if (op.fixed()[static_cast<std::size_t>(node)]) continue;
    for (int d = 0; d < 3; ++d)
      t.emplace_back(3 * node + d, 3 * node + d, factor * op.mass()[node]);
  }
}

/// The boundary's 3 x 3 blocks, springs (S) or dashpots (D).
void add_boundary(const SoilOperator& op, bool springs, Triplets& t) {
  for (const BoundaryNode& b : op.boundary()) {
    if (op.fixed()[static_cast<std::size_t>(b.node)]) continue;
    for (int d = 0; d < 3; ++d) {
      double unit[3] = {0.0, 0.0, 0.0}, column[3] = {0.0, 0.0, 0.0};
      unit[d] = 1.0;
      if (springs)
        b.apply_spring(unit, column);
      else
        b.apply_dashpot(unit, column);
      for (int c = 0; c < 3; ++c)
        if (column[c] != 0.0) t.emplace_back(3 * b.node + c, 3 * b.node + d, column[c]);
    }
  }
}

void to_csc(const Sparse& a, CscMatrix& out) {
  out.rows = static_cast<std::uint64_t>(a.rows());
  out.cols = static_cast<std::uint64_t>(a.cols());
  out.col_ptr.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1);
  out.row_index.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  out.values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
}

}  // namespace

void linear_matrix(const SoilOperator& op, const FootprintWeights& weights, double a0, double a1,
                   rumble_matrix which, CscMatrix& out) {
  const std::int64_t n = op.dofs();
  Triplets t;
  Sparse a(n, which == RUMBLE_MATRIX_INPUT ? static_cast<std::int64_t>(weights.size()) : n);
  switch (which) {
    case RUMBLE_MATRIX_MASS:
      add_mass(op, 1.0, t);
      break;
    case RUMBLE_MATRIX_DAMPING:
      add_mass(op, a0, t);
      if (a1 != 0.0) add_stiffness(op, a1, t);
      add_boundary(op, false, t);
      break;
    case RUMBLE_MATRIX_STIFFNESS:
      add_stiffness(op, 1.0, t);
      if (op.springs_act()) add_boundary(op, true, t);
      for (std::size_t node = 0; node < op.fixed().size(); ++node)
        if (op.fixed()[node])
          for (std::int64_t d = 0; d < 3; ++d)
            t.emplace_back(3 * static_cast<std::int64_t>(node) + d,
                           3 * static_cast<std::int64_t>(node) + d, 1.0);
      break;
    case RUMBLE_MATRIX_INPUT:
      for (std::size_t j = 0; j < weights.size(); ++j)
        for (const NodalWeight& w : weights[j])
          if (!op.fixed()[static_cast<std::size_t>(w.node)])
            t.emplace_back(3 * static_cast<std::int64_t>(w.node) + 2, static_cast<std::int64_t>(j),
                           w.weight);
      break;
    default:
      throw std::invalid_argument("fem: linear_matrix: no matrix number " +
                                  std::to_string(static_cast<int>(which)) + " (0..3: M, C, K, B)");
  }
  a.setFromTriplets(t.begin(), t.end());  // sums duplicates; rows sorted per column
  a.makeCompressed();
  to_csc(a, out);
}

}  // namespace rumble::fem
