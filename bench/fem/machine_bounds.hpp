// The two bounds of a kernel on this machine, measured in the benchmark's own process: the
// memory bandwidth (a STREAM-like triad) and the peak rate of fused multiply-adds at the SIMD
// width the explicit step's product runs (4 doubles with AVX2 and FMA where the processor has
// them, as operator/block_kernel_avx2.hpp; else 2 doubles, multiply then add, the baseline
// x86-64's SSE2). A kernel's time is bounded below by bytes / bandwidth and by flops / peak;
// whichever is longer applies (docs/fem-soil.md §4.3).
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "operator/block_view.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RUMBLE_BENCH_FMA 1
#include <immintrin.h>
#else
#define RUMBLE_BENCH_FMA 0
#endif

namespace rumble::bench {

/// Triad a = b + s c over n doubles with `threads` threads: best bandwidth [B/s] of 20 passes,
/// counting 24 B per element (two reads, one write).
inline double triad_bandwidth(std::int64_t n, int threads) {
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 0.0;
  for (int pass = 0; pass < 20; ++pass) {
    const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, 24.0 * static_cast<double>(n) / s);
  }
  benchmark::DoNotOptimize(a.data());
  return best;
}

namespace detail {

constexpr int kChains = 12;  // independent multiply-adds in flight: > latency x pipes (4 x 2)

#if RUMBLE_BENCH_FMA
/// `rounds` x 12 fused multiply-adds of 4 doubles: flops done.
__attribute__((target("avx2,fma"))) inline double fma_rounds(std::int64_t rounds) {
  __m256d acc[kChains];
  for (int k = 0; k < kChains; ++k) acc[k] = _mm256_set1_pd(1.0 + 1e-3 * k);
  const __m256d a = _mm256_set1_pd(0.999999), b = _mm256_set1_pd(1e-7);
  for (std::int64_t r = 0; r < rounds; ++r)
    for (int k = 0; k < kChains; ++k) acc[k] = _mm256_fmadd_pd(acc[k], a, b);
  for (int k = 1; k < kChains; ++k) acc[0] = _mm256_add_pd(acc[0], acc[k]);
  benchmark::DoNotOptimize(acc[0]);
  return 8.0 * kChains * static_cast<double>(rounds);
}
#endif

/// The same without FMA: a multiply and an add of 2 doubles per chain and round.
inline double mul_add_rounds(std::int64_t rounds) {
  using Pair = double __attribute__((vector_size(16)));
  Pair acc[kChains];
  for (int k = 0; k < kChains; ++k) acc[k] = Pair{1.0, 1.0} + 1e-3 * k;
  const Pair a = {0.999999, 0.999999}, b = {1e-7, 1e-7};
  for (std::int64_t r = 0; r < rounds; ++r)
    for (int k = 0; k < kChains; ++k) acc[k] = acc[k] * a + b;
  for (int k = 1; k < kChains; ++k) acc[0] += acc[k];
  benchmark::DoNotOptimize(acc[0]);
  return 4.0 * kChains * static_cast<double>(rounds);
}

}  // namespace detail

/// Peak flops per second [flop/s] of `threads` threads, each running independent chains of
/// multiply-adds at the step's SIMD width (best of 20 passes of about 3 ms).
inline double peak_flops(int threads) {
  constexpr std::int64_t kRounds = 1 << 20;
  [[maybe_unused]] const bool fma = fem::block_simd_available();
  double best = 0.0;
  for (int pass = 0; pass < 20; ++pass) {
    double flops = 0.0;
    const auto start = std::chrono::steady_clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : flops)
    {
#if RUMBLE_BENCH_FMA
      flops += fma ? detail::fma_rounds(kRounds) : detail::mul_add_rounds(kRounds);
#else
      flops += detail::mul_add_rounds(kRounds);
#endif
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, flops / s);
  }
  return best;
}

}  // namespace rumble::bench
