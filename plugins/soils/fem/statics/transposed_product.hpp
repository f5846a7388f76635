// y = P^T x from P's own rows, so that multigrid's restriction R = P^T need not be stored beside
// the prolongator P (amg_preconditioner.hpp): on the mesh's level that is 0.22 GB at 1e6 DOFs,
// a seventh of the statics' peak (docs/fem-soil.md section 7.2). Each coarse row's sum runs over
// the fine rows in ascending order from 0, as R's row product would run, so y is the same to the
// bit. The coarse rows are shared out among the threads in ranges; a thread reads only the fine
// rows that reach its range (listed once), so P is read about once per product.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "operator/sparse_product.hpp"

namespace rumble::fem {

class TransposedProduct {
 public:
  TransposedProduct() = default;
  /// For P (compressed), its coarse rows in `parts` ranges (the threads of the products).
  TransposedProduct(const RowSparseFloat& P, unsigned parts);

  /// y = P^T x (y resized to P's columns).
  void multiply(const RowSparseFloat& P, const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  std::size_t bytes() const;

 private:
  std::vector<Eigen::Index> part_start_;            // parts + 1 coarse rows
  std::vector<std::vector<std::int32_t>> reaches_;  // per part: the fine rows with an entry there
};

}  // namespace rumble::fem
