// The symmetric blocks' product (symmetric_blocks.hpp) on AVX2 with FMA (x86-64-v3): each of a
// block's 3 rows in one register of 4 doubles (the 4th lane is the next value, multiplied by a
// zero or dropped), so a block takes 3 row loads (converted from float where K is read in single
// precision), one masked load of x_j and 6 fused multiply-adds, against 18 multiplies, 18 adds and
// 9 conversions one value at a time:
//   node i's sums:   acc_c += K_ij[c][0..2] * x_j[0..2]  (lane by lane; summed across at the end)
//   node j's:        s_j   += K_ij[0][..] x_i0 + K_ij[1][..] x_i1 + K_ij[2][..] x_i2
// The functions carry their target, so the build stays for any x86-64: the blocks call them only
// where the processor has AVX2 and FMA (block_simd_available). Included by symmetric_blocks.cpp
// alone; measured in docs/fem-soil.md §4.3.
#pragma once

#include <cstdint>

#include "operator/block_view.hpp"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define RUMBLE_BLOCK_KERNEL_AVX2 1
#include <immintrin.h>
#else
#define RUMBLE_BLOCK_KERNEL_AVX2 0
#endif

#if RUMBLE_BLOCK_KERNEL_AVX2
namespace rumble::fem::block_kernel_avx2 {

#define RUMBLE_AVX2_FMA __attribute__((target("avx2,fma")))
#define RUMBLE_AVX2_FMA_INLINE __attribute__((target("avx2,fma"), always_inline)) inline

/// A block's rows (lane 3: the next stored value, finite; never reaches a result).
struct Rows {
  __m256d r0, r1, r2;
};
/// A node's x, each component in every lane.
struct Broadcast {
  __m256d x0, x1, x2;
};
/// Node i's sums lane by lane: a0[d] = sum_j K_ij[0][d] x_j[d], ...
struct Sums {
  __m256d a0, a1, a2;
};

RUMBLE_AVX2_FMA_INLINE __m256d row(const float* b) {
  return _mm256_cvtps_pd(_mm_loadu_ps(b));
}
RUMBLE_AVX2_FMA_INLINE __m256d row(const double* b) {
  return _mm256_loadu_pd(b);
}
template <class Value>
RUMBLE_AVX2_FMA_INLINE Rows rows(const Value* b) {
  return {row(b), row(b + 3), row(b + 6)};
}
/// x_j in lanes 0-2, lane 3 zero (never read: x may end there).
RUMBLE_AVX2_FMA_INLINE __m256d node_x(const double* xj) {
  return _mm256_maskload_pd(xj, _mm256_set_epi64x(0, -1, -1, -1));
}
RUMBLE_AVX2_FMA_INLINE Broadcast broadcast(const double* xi) {
  return {_mm256_broadcast_sd(xi), _mm256_broadcast_sd(xi + 1), _mm256_broadcast_sd(xi + 2)};
}
RUMBLE_AVX2_FMA_INLINE void add_product(const Rows& k, __m256d xj, Sums& s) {
  s.a0 = _mm256_fmadd_pd(k.r0, xj, s.a0);
  s.a1 = _mm256_fmadd_pd(k.r1, xj, s.a1);
  s.a2 = _mm256_fmadd_pd(k.r2, xj, s.a2);
}
/// s_j += K_ij^T x_i: the same operations wherever it is called (in the sweep or for a cross
/// block), so a node's sum is the same on any number of parts.
RUMBLE_AVX2_FMA_INLINE void add_transposed(const Rows& k, const Broadcast& xi, NodeSum& sj) {
  __m256d t = _mm256_mul_pd(k.r0, xi.x0);
  t = _mm256_fmadd_pd(k.r1, xi.x1, t);
  t = _mm256_fmadd_pd(k.r2, xi.x2, t);
  _mm256_store_pd(sj.v, _mm256_add_pd(_mm256_load_pd(sj.v), t));
}
/// {sum of a0's lanes, of a1's, of a2's, -}: (lane 0 + lane 1) + (lane 2 + lane 3).
RUMBLE_AVX2_FMA_INLINE __m256d across(const Sums& s) {
  const __m256d h01 = _mm256_hadd_pd(s.a0, s.a1), h2 = _mm256_hadd_pd(s.a2, s.a2);
  return _mm256_add_pd(_mm256_permute2f128_pd(h01, h2, 0x20),
                       _mm256_permute2f128_pd(h01, h2, 0x31));
}

/// Block q of node i (j = its column): into node i's sums, and into node j's pending sum when j
/// is in the part (a later part gathers its own). Asks for block q + kPrefetchAhead's values, x
/// and pending sum first, and block q + kFarPrefetchAhead's values into the second-level cache
/// (block_view.hpp).
template <class Value>
RUMBLE_AVX2_FMA_INLINE void off_diagonal(const BlockView<Value>& v, std::int64_t q, const double* x,
                                         const Broadcast& xi, NodeSum* scratch, Sums& sums) {
  const std::int64_t j = v.column[q], ahead = v.column[q + kPrefetchAhead];
  _mm_prefetch(reinterpret_cast<const char*>(x + 3 * ahead), _MM_HINT_T0);
  _mm_prefetch(reinterpret_cast<const char*>(scratch + ahead), _MM_HINT_T0);
  _mm_prefetch(reinterpret_cast<const char*>(v.value + 9 * (q + kPrefetchAhead)), _MM_HINT_T0);
  _mm_prefetch(reinterpret_cast<const char*>(v.value + 9 * (q + kFarPrefetchAhead)), _MM_HINT_T1);
  const Rows k = rows(v.value + 9 * q);
  add_product(k, node_x(x + 3 * j), sums);
  if (j < v.end) add_transposed(k, xi, scratch[j]);
}

/// The part's cross blocks into its nodes' pending sums.
template <class Value>
RUMBLE_AVX2_FMA void gather_cross(const BlockView<Value>& part, const double* x, NodeSum* scratch) {
  const BlockView<Value> v = part;  // (a local copy stays in registers across the stores)
  for (std::int64_t c = v.cross_begin; c < v.cross_end; ++c) {
    const std::int64_t q = v.cross_block[c];
    add_transposed(rows(v.value + 9 * q), broadcast(x + 3 * std::int64_t{v.cross_from[c]}),
                   scratch[v.column[q]]);
  }
}

/// The part's nodes [first, last) in ascending order, after the earlier ones and its cross
/// blocks: out[4 (i - first) + c] = (K x) at node i, DOF c, and node i's pending sum zeroed.
/// Two sets of sums (even and odd blocks) keep two multiply-adds in flight.
template <class Value>
RUMBLE_AVX2_FMA void sweep(const BlockView<Value>& part, std::int64_t first, std::int64_t last,
                           const double* x, NodeSum* scratch, double* out) {
  const BlockView<Value> v = part;
  const __m256d zero = _mm256_setzero_pd();
  for (std::int64_t i = first; i < last; ++i) {
    const std::int64_t begin = v.block_start[i], end = v.block_start[i + 1];
    const Rows diagonal = rows(v.value + 9 * begin);
    const __m256d own = node_x(x + 3 * i);
    Sums even{_mm256_mul_pd(diagonal.r0, own), _mm256_mul_pd(diagonal.r1, own),
              _mm256_mul_pd(diagonal.r2, own)};
    Sums odd{zero, zero, zero};
    const Broadcast xi = broadcast(x + 3 * i);
    std::int64_t q = begin + 1;
    for (; q + 1 < end; q += 2) {
      off_diagonal(v, q, x, xi, scratch, even);
      off_diagonal(v, q + 1, x, xi, scratch, odd);
    }
    if (q < end) off_diagonal(v, q, x, xi, scratch, even);
    const Sums both{_mm256_add_pd(even.a0, odd.a0), _mm256_add_pd(even.a1, odd.a1),
                    _mm256_add_pd(even.a2, odd.a2)};
    _mm256_storeu_pd(out + 4 * (i - first),
                     _mm256_add_pd(_mm256_load_pd(scratch[i].v), across(both)));
    _mm256_store_pd(scratch[i].v, zero);
  }
}

#undef RUMBLE_AVX2_FMA_INLINE
#undef RUMBLE_AVX2_FMA

}  // namespace rumble::fem::block_kernel_avx2
#endif
