#include "statics/transposed_product.hpp"

#include <algorithm>

namespace rumble::fem {

TransposedProduct::TransposedProduct(const RowSparseFloat& P, unsigned parts) {
  const auto count = static_cast<Eigen::Index>(std::max(1u, parts));
  for (Eigen::Index t = 0; t <= count; ++t) part_start_.push_back(P.cols() * t / count);
  reaches_.resize(static_cast<std::size_t>(count));
  const auto part_of = [&](Eigen::Index column) {
    return static_cast<std::size_t>(
        std::upper_bound(part_start_.begin(), part_start_.end(), column) - part_start_.begin() - 1);
  };
  for (Eigen::Index k = 0; k < P.rows(); ++k)
    for (int e = P.outerIndexPtr()[k]; e < P.outerIndexPtr()[k + 1]; ++e) {
      std::vector<std::int32_t>& rows = reaches_[part_of(P.innerIndexPtr()[e])];
      if (rows.empty() || rows.back() != k) rows.push_back(static_cast<std::int32_t>(k));
    }
}

void TransposedProduct::multiply(const RowSparseFloat& P, const Eigen::VectorXd& x,
                                 Eigen::VectorXd& y) const {
  y.resize(P.cols());
  const int* start = P.outerIndexPtr();
  const int* column = P.innerIndexPtr();
  const float* value = P.valuePtr();
  const auto parts = static_cast<std::int64_t>(reaches_.size());
#pragma omp parallel for num_threads(static_cast <int>(parts)) schedule(static, 1)
  for (std::int64_t t = 0; t < parts; ++t) {
    const Eigen::Index first = part_start_[static_cast<std::size_t>(t)];
    const Eigen::Index last = part_start_[static_cast<std::size_t>(t) + 1];
    for (Eigen::Index I = first; I < last; ++I) y[I] = 0.0;
    for (const std::int32_t k : reaches_[static_cast<std::size_t>(t)]) {
      // (columns ascending: the part's entries of row k are one run)
      const int* at = std::lower_bound(column + start[k], column + start[k + 1], first);
      for (; at != column + start[k + 1] && *at < last; ++at) y[*at] += value[at - column] * x[k];
    }
  }
}

std::size_t TransposedProduct::bytes() const {
  std::size_t b = part_start_.size() * 8;
  for (const auto& rows : reaches_) b += rows.size() * 4;
  return b;
}

}  // namespace rumble::fem
