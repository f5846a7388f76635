#include "operator/csr_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rumble::fem {

CsrMatrix::CsrMatrix(const TetMesh& mesh) {
  const std::int64_t n = mesh.node_count();
  // Node graph: every pair of nodes of a tetrahedron (self included), counted, filled, sorted
  // and made unique per node; then compacted.
  std::vector<std::int64_t> count(n + 1, 0);
  for (const Tetrahedron& t : mesh.tets)
    for (std::int32_t a : t) count[a + 1] += 4;
  for (std::int64_t i = 0; i < n; ++i) count[i + 1] += count[i];
  std::vector<std::int32_t> raw(count[n]);
  std::vector<std::int64_t> fill(count.begin(), count.end() - 1);
  for (const Tetrahedron& t : mesh.tets)
    for (std::int32_t a : t)
      for (std::int32_t b : t) raw[fill[a]++] = b;
  neighbour_start_.assign(n + 1, 0);
  neighbour_.reserve(raw.size() / 3);
  for (std::int64_t i = 0; i < n; ++i) {
    auto first = raw.begin() + count[i], last = raw.begin() + count[i + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    neighbour_.insert(neighbour_.end(), first, last);
    neighbour_start_[i + 1] = static_cast<std::int64_t>(neighbour_.size());
  }
  // DOF rows: row 3 i + c starts at 9 start(i) + 3 c deg(i).
  row_start_.assign(3 * n + 1, 0);
  column_.resize(9 * neighbour_.size());
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t deg = neighbour_start_[i + 1] - neighbour_start_[i];
    for (int c = 0; c < 3; ++c) {
      const std::int64_t start = 9 * neighbour_start_[i] + 3 * c * deg;
      row_start_[3 * i + c] = start;
      for (std::int64_t p = 0; p < deg; ++p)
        for (int d = 0; d < 3; ++d)
          column_[start + 3 * p + d] = 3 * neighbour_[neighbour_start_[i] + p] + d;
    }
  }
  row_start_[3 * n] = static_cast<std::int64_t>(column_.size());
  value_.assign(column_.size(), 0.0);
}

double* CsrMatrix::block_row(std::int32_t i, std::int32_t j, int c) {
  const auto first = neighbour_.begin() + neighbour_start_[i];
  const auto last = neighbour_.begin() + neighbour_start_[i + 1];
  const auto it = std::lower_bound(first, last, j);
  if (it == last || *it != j) throw std::out_of_range("CsrMatrix: nodes are not neighbours");
  return value_.data() + row_start_[3 * static_cast<std::int64_t>(i) + c] + 3 * (it - first);
}

CsrMatrix::Rows CsrMatrix::release_rows() && {
  Rows r{std::move(row_start_), std::move(column_), std::move(value_)};
  std::vector<std::int64_t>().swap(neighbour_start_);
  std::vector<std::int32_t>().swap(neighbour_);
  row_start_.assign(1, 0);  // (an empty matrix: rows() 0)
  return r;
}

std::vector<double> CsrMatrix::diagonal() const {
  std::vector<double> d(static_cast<std::size_t>(rows()), 0.0);
  for (std::int64_t r = 0; r < rows(); ++r)
    for (std::int64_t k = row_start_[r]; k < row_start_[r + 1]; ++k)
      if (column_[k] == r) d[r] = value_[k];
  return d;
}

std::vector<double> CsrMatrix::magnitude_sums() const {
  std::vector<double> sums(static_cast<std::size_t>(rows()), 0.0);
  for (std::int64_t r = 0; r < rows(); ++r)
    for (std::int64_t k = row_start_[r]; k < row_start_[r + 1]; ++k) sums[r] += std::abs(value_[k]);
  return sums;
}

std::vector<std::int32_t> CsrMatrix::flagged_neighbours(const std::vector<char>& flag) const {
  const auto nodes = static_cast<std::int32_t>(neighbour_start_.size()) - 1;
  std::vector<std::int32_t> count(static_cast<std::size_t>(nodes), 0);
  for (std::int32_t i = 0; i < nodes; ++i)
    for (std::int64_t q = 0; q < degree(i); ++q) count[i] += flag[neighbours(i)[q]] ? 1 : 0;
  return count;
}

void CsrMatrix::multiply_rows(const double* x, double* y, std::int64_t begin,
                              std::int64_t end) const {
  for (std::int64_t r = begin; r < end; ++r) y[r] = row_dot(r, x);
}

}  // namespace rumble::fem
