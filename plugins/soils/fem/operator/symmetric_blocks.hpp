// K's upper block triangle, for the explicit step's product: each off-diagonal 3 x 3 block
// (i, j > i) is read once and used twice, K_ij x_j into node i's row and K_ij^T x_i into node
// j's, so the step streams half of K's values and node indices (docs/numerics.md §5: the step is
// bound by memory traffic, and K's values were 2/3 of it). The operator is symmetric by
// construction.
//
// The product runs over contiguous node ranges ("parts", one per thread). Within a part, nodes
// go in ascending order: when node i is reached, every node before it in the part has added its
// K_ki^T x_k, so node i's row is complete after its own blocks and is handed to the caller at
// once (the step finishes the node there, as with full rows). Blocks from an earlier part into
// a later one are gathered by the later part first ("cross" blocks, listed per part), so no two
// threads write the same entry.
#pragma once

#include <omp.h>

#include <cstdint>
#include <vector>

#include "operator/csr_matrix.hpp"

namespace rumble::fem {

template <class Value>
class SymmetricBlocks {
 public:
  /// K's blocks (i, j >= i), rounded to Value; parts: how many node ranges the product has.
  SymmetricBlocks(const CsrMatrix& K, unsigned parts);

  std::int64_t nodes() const { return static_cast<std::int64_t>(block_start_.size()) - 1; }
  unsigned parts() const { return static_cast<unsigned>(part_start_.size()) - 1; }
  /// Splits the nodes into `parts` ranges of equal size (the threads of the step).
  void set_parts(unsigned parts);
  std::size_t bytes() const;

  /// For each node i: out = (K x) at node i's 3 DOFs, handed to finish(i, out) by the thread
  /// that owns node i's part. Called by every thread of an OpenMP team (of any size; the parts
  /// are shared out among them). x must be complete before (a barrier) and stays unchanged;
  /// scratch: 3 x nodes() doubles, zero before the call and left zero after it. No barrier at
  /// the end.
  template <class Finish>
  void multiply(const double* x, double* scratch, Finish&& finish) const;

 private:
  std::vector<std::int64_t> block_start_;  // node i's blocks: the diagonal, then j > i ascending
  std::vector<std::int32_t> column_;       // per block: its node j
  std::vector<Value> value_;               // per block: 9, row-major (K_ij)
  std::vector<std::int64_t> part_start_;   // parts + 1 node indices
  // Per part: the blocks (k, j) with k before the part and j in it.
  std::vector<std::int64_t> cross_start_;  // parts + 1
  std::vector<std::int32_t> cross_from_;   // k
  std::vector<std::int64_t> cross_block_;  // the block's index
};

template <class Value>
template <class Finish>
void SymmetricBlocks<Value>::multiply(const double* x, double* scratch, Finish&& finish) const {
  const int team = omp_get_num_threads();
  const auto count = static_cast<int>(parts());
  for (int p = omp_get_thread_num(); p < count; p += team) {
    for (std::int64_t c = cross_start_[p]; c < cross_start_[p + 1]; ++c) {
      const Value* b = value_.data() + 9 * cross_block_[c];
      const double* xk = x + 3 * static_cast<std::int64_t>(cross_from_[c]);
      double* sj = scratch + 3 * static_cast<std::int64_t>(column_[cross_block_[c]]);
      for (int d = 0; d < 3; ++d)
        sj[d] += double(b[d]) * xk[0] + double(b[3 + d]) * xk[1] + double(b[6 + d]) * xk[2];
    }
    const std::int64_t end = part_start_[p + 1];
    for (std::int64_t i = part_start_[p]; i < end; ++i) {
      const double* xi = x + 3 * i;
      double* si = scratch + 3 * i;
      const std::int64_t first = block_start_[i], last = block_start_[i + 1];
      const Value* b = value_.data() + 9 * first;  // the diagonal block
      double out[3];
      for (int c = 0; c < 3; ++c) {
        out[c] = si[c] + double(b[3 * c]) * xi[0] + double(b[3 * c + 1]) * xi[1] +
                 double(b[3 * c + 2]) * xi[2];
        si[c] = 0.0;
      }
      for (std::int64_t q = first + 1; q < last; ++q) {
        b += 9;
        const std::int64_t j = column_[q];
        const double* xj = x + 3 * j;
        out[0] += double(b[0]) * xj[0] + double(b[1]) * xj[1] + double(b[2]) * xj[2];
        out[1] += double(b[3]) * xj[0] + double(b[4]) * xj[1] + double(b[5]) * xj[2];
        out[2] += double(b[6]) * xj[0] + double(b[7]) * xj[1] + double(b[8]) * xj[2];
        if (j < end) {  // (a later part gathers its own)
          double* sj = scratch + 3 * j;
          sj[0] += double(b[0]) * xi[0] + double(b[3]) * xi[1] + double(b[6]) * xi[2];
          sj[1] += double(b[1]) * xi[0] + double(b[4]) * xi[1] + double(b[7]) * xi[2];
          sj[2] += double(b[2]) * xi[0] + double(b[5]) * xi[1] + double(b[8]) * xi[2];
        }
      }
      finish(i, out);
    }
  }
}

}  // namespace rumble::fem
