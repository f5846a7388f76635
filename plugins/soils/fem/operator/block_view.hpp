// The kernels of the symmetric blocks' product (symmetric_blocks.hpp): which there are, what one
// reads of a part, and the sums it keeps per node.
#pragma once

#include <cstdint>

namespace rumble::fem {

/// The symmetric blocks' product's kernels: one value at a time, or a block's row per SIMD
/// register (AVX2 and FMA: block_kernel_avx2.hpp).
enum class BlockKernel { kPortable, kSimd };

/// Whether this processor (and its operating system) runs the SIMD kernel.
bool block_simd_available();

/// A node's pending sum (K_ki^T x_k from the nodes k before it): its 3 DOFs, padded to one
/// 32-B line of 4 doubles, so that the SIMD kernel adds a block's 3 values with one load and one
/// store and never touches a neighbour's (block_kernel_avx2.hpp).
struct alignas(32) NodeSum {
  double v[4];
};

/// How many blocks ahead the kernels ask the cache for the x, the pending sum and the values that
/// a later block will read (docs/fem-soil.md §4.3, "Gathers"). On a gmsh mesh a block's node j is
/// not where the hardware prefetcher looks, and the sweep waited on those loads: asking 64 blocks
/// (about 8 nodes) ahead made the step 1.14-1.35x faster on the stiff example's 1.0e6-DOF mesh
/// (48 to 128 blocks within 3 % of each other on a 1.3e6-DOF one), and left a structured box's
/// as it was. K's values are a plain stream, but among the sweep's dozen others (x and the pending
/// sums on each neighbour's stride, the node's vectors) the hardware prefetcher did not keep up
/// with it on an AVX-512 EPYC: asking for them too made the step in single precision 1.27x faster
/// on the box and 1.05x on the gmsh mesh (§4.3, "K's values ahead").
inline constexpr std::int64_t kPrefetchAhead = 64;

/// How many blocks ahead the SIMD kernel also asks the second-level cache for K's values: a
/// software prefetch into the first level holds one of its few outstanding misses until the line
/// arrives from memory, one into the second leaves them to the sweep's loads, so more of the value
/// stream is on its way while the sweep computes. On the AVX-512 EPYC it made the box's step 1.10x
/// faster beyond the L3 (1.07e6 DOFs, single precision, 2 threads; medians) and 1.14x at 3.1e5
/// DOFs in double; the graded gmsh mesh's, which waits on its gathers, and the portable kernel's,
/// which waits on its arithmetic, not at all (docs/fem-soil.md §4.3, "K's values further ahead").
/// `value` has this many blocks of zeros after the last.
inline constexpr std::int64_t kFarPrefetchAhead = 4 * kPrefetchAhead;

/// One part of the blocks: its nodes [begin, end), its cross blocks [cross_begin, cross_end)
/// and the arrays they index (symmetric_blocks.hpp has their layout; `column` has
/// kPrefetchAhead zeros after the last block and `value` kFarPrefetchAhead blocks of zeros, which
/// the look-ahead reads).
template <class Value>
struct BlockView {
  std::int64_t begin, end, cross_begin, cross_end;
  const std::int64_t* block_start;
  const std::int32_t* column;
  const Value* value;
  const std::int32_t* cross_from;
  const std::int64_t* cross_block;
};

}  // namespace rumble::fem
