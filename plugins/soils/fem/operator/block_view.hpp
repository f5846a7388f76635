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

/// One part of the blocks: its nodes [begin, end), its cross blocks [cross_begin, cross_end)
/// and the arrays they index (symmetric_blocks.hpp has their layout; `column` has
/// kPrefetchAhead zeros after the last block, which the look-ahead reads).
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
