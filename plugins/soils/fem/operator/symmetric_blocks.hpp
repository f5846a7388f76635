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
// threads write the same entry. Every sum into a node runs in ascending order of the node it
// comes from on any number of parts, so the product is the same to the bit on any team.
//
// Two kernels compute the nodes' products, a run of up to kRun nodes at a time (docs/fem-soil.md
// §4.3): a SIMD one (block_kernel_avx2.hpp, a block's row per 4-double register) where the
// processor has AVX2 and FMA (x86-64-v3; chosen at run time, the build targets any x86-64), and
// a portable one, one value at a time, elsewhere. They agree to rounding (the SIMD kernel fuses
// its multiply-adds), each the same on any team. The caller's finish runs on each run after its
// kernel, in the caller's own code: the same arithmetic whichever kernel ran.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "operator/block_view.hpp"
#include "operator/csr_matrix.hpp"

namespace rumble::fem {

template <class Value>
class SymmetricBlocks {
 public:
  /// Nodes per kernel call: their products wait in 32 B each on the stack (in L1).
  static constexpr std::int64_t kRun = 64;

  /// K's blocks (i, j >= i), rounded to Value; parts: how many node ranges the product has.
  /// The kernel: the SIMD one where the processor runs it.
  SymmetricBlocks(const CsrMatrix& K, unsigned parts);
  /// The same with K's nodes taken in `order` (order[p]: the node at place p, each node once;
  /// else std::invalid_argument): the blocks (i, j) with j at or after i in the order, and every
  /// node index below (x, scratch, finish, parts) a place in the order. Each node's sum then runs
  /// as with K renumbered in that order: the ranks' parts (distributed/distributed_operator.hpp)
  /// sum each interior node's product in one process's order, so to the bit as one process.
  SymmetricBlocks(const CsrMatrix& K, unsigned parts, const std::vector<std::int32_t>& order);

  std::int64_t nodes() const { return static_cast<std::int64_t>(block_start_.size()) - 1; }
  unsigned parts() const { return static_cast<unsigned>(part_start_.size()) - 1; }
  /// Splits the nodes into `parts` ranges of equal size (the threads of the step).
  void set_parts(unsigned parts);
  /// Splits the nodes at `starts` (parts + 1 node indices, ascending, 0 first and nodes() last;
  /// a part may be empty): for a caller that multiplies some parts before others
  /// (multiply_parts). Else std::invalid_argument.
  void set_part_starts(const std::vector<std::int64_t>& starts);
  std::size_t bytes() const;
  BlockKernel kernel() const { return kernel_; }
  /// Chooses the kernel (tests and benchmarks); kSimd where the processor cannot run it:
  /// std::invalid_argument.
  void set_kernel(BlockKernel kernel);

  /// Each block once, in ascending order: visit(i, j, values) for the diagonal (j == i) and
  /// each block (i, j) with j after i, K_ij's 9 values row-major (K_ji is its transpose); i and
  /// j are places in the order where one was given. For set-ups that read K as the step does.
  template <class Visit>
  void for_each_block(Visit&& visit) const {
    for (std::int64_t i = 0; i < nodes(); ++i)
      for (std::int64_t q = block_start_[i]; q < block_start_[i + 1]; ++q)
        visit(static_cast<std::int32_t>(i), column_[q], value_.data() + 9 * q);
  }

  /// For each node i: out = (K x) at node i's 3 DOFs, handed to finish(i, out) by the thread
  /// that owns node i's part, in ascending order. Called by every thread of an OpenMP team (of
  /// any size; the parts are shared out among them). x must be complete before (a barrier) and
  /// stays unchanged; scratch: nodes() sums, zero before the call and left zero after it. No
  /// barrier at the end.
  template <class Finish>
  void multiply(const double* x, NodeSum* scratch, Finish&& finish) const {
    multiply_parts(0, parts(), x, scratch, finish);
  }
  /// The same over the parts [first_part, last_part) alone: their nodes' products are complete
  /// without the other parts' (a part gathers the blocks from earlier parts itself), so the parts
  /// may be multiplied in any order and in several calls, each on the whole team.
  template <class Finish>
  void multiply_parts(unsigned first_part, unsigned last_part, const double* x, NodeSum* scratch,
                      Finish&& finish) const;

 private:
  BlockView<Value> view(std::int64_t part) const;
  /// The part's cross blocks into its nodes' pending sums, by the chosen kernel.
  void gather_cross(const BlockView<Value>& v, const double* x, NodeSum* scratch) const;
  /// Nodes [first, last) of the part (at most kRun, in order): out[4 (i - first) + c] = (K x)
  /// at node i, DOF c, by the chosen kernel.
  void sweep(const BlockView<Value>& v, std::int64_t first, std::int64_t last, const double* x,
             NodeSum* scratch, double* out) const;

  std::vector<std::int64_t> block_start_;  // node i's blocks: the diagonal, then j > i ascending
  std::vector<std::int32_t> column_;       // per block: its node j
  // Per block: 9, row-major (K_ij); then kFarPrefetchAhead blocks of zeros, which the SIMD
  // kernel's last row load and the look-ahead read.
  std::vector<Value> value_;
  std::vector<std::int64_t> part_start_;  // parts + 1 node indices
  // Per part: the blocks (k, j) with k before the part and j in it.
  std::vector<std::int64_t> cross_start_;  // parts + 1
  std::vector<std::int32_t> cross_from_;   // k
  std::vector<std::int64_t> cross_block_;  // the block's index
  BlockKernel kernel_ = BlockKernel::kPortable;
};

template <class Value>
template <class Finish>
void SymmetricBlocks<Value>::multiply_parts(unsigned first_part, unsigned last_part,
                                            const double* x, NodeSum* scratch,
                                            Finish&& finish) const {
  const int team = omp_get_num_threads();
  const auto count = static_cast<int>(std::min(last_part, parts()));
  alignas(32) double out[4 * kRun];
  for (int p = static_cast<int>(first_part) + omp_get_thread_num(); p < count; p += team) {
    const BlockView<Value> v = view(p);
    gather_cross(v, x, scratch);
    for (std::int64_t first = v.begin; first < v.end; first += kRun) {
      const std::int64_t last = std::min(v.end, first + kRun);
      sweep(v, first, last, x, scratch, out);
      for (std::int64_t i = first; i < last; ++i)
        finish(i, static_cast<const double*>(out + 4 * (i - first)));
    }
  }
}

}  // namespace rumble::fem
