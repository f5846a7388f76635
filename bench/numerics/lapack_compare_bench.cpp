// Our banded and tridiagonal solvers against LAPACK's (issue #31: general numerics from maintained
// libraries, unless our own is measurably faster): the track's banded Cholesky
// (engine/track/include/track/banded_matrix.hpp) against dpbtrf/dpbtrs, and the reduced soils'
// tridiagonal LU (plugins/soils/common/tridiagonal_lu.hpp), real and complex, against
// ?gttrf/?gttrs (the _work entry points: no NaN scan, no allocation). Same matrices, same right
// -hand sides, one run, so the ratios hold on whatever machine runs it:
//   OPENBLAS_NUM_THREADS=1 build/release/bin/lapack_compare_bench --benchmark_min_time=0.2
// Sizes: the track has n = 3 x nodes DOFs within half-bandwidth 4 (8 with the integrated soil's
// condensation, 24 at most for its widest layouts); the reduced soils have one DOF per footprint.
#include <benchmark/benchmark.h>
#include <lapacke.h>

#include <complex>
#include <random>
#include <vector>

#include "track/banded_matrix.hpp"
#include "tridiagonal_lu.hpp"

namespace {

// A diagonally dominant symmetric banded matrix of size n and half-bandwidth b, in our storage
// and in LAPACK's lower band storage (the same layout: column j holds A(j..j+b, j)).
struct Banded {
  rumble::BandedSymmetric ours;
  std::vector<double> lapack;
};

Banded banded(int n, int b) {
  Banded m{rumble::BandedSymmetric(n, b), std::vector<double>((b + 1) * n)};
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < n; ++j) {
    m.ours.add(j, j, 4.0 * b);
    for (int k = 1; k <= b && j + k < n; ++k) m.ours.add(j + k, j, u(g));
  }
  for (int j = 0; j < n; ++j)
    for (int i = j; i <= std::min(n - 1, j + b); ++i)
      m.lapack[(i - j) + (b + 1) * j] = m.ours.at(i, j);
  return m;
}

void BM_BandedFactor(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), b = static_cast<int>(state.range(1));
  const bool lapack = state.range(2) != 0;
  const Banded m = banded(n, b);
  for (auto _ : state) {
    Banded work = m;  // the copy is timed for both, as factoring overwrites the matrix
    if (lapack)
      LAPACKE_dpbtrf_work(LAPACK_COL_MAJOR, 'L', n, b, work.lapack.data(), b + 1);
    else
      work.ours.factorize();
    benchmark::DoNotOptimize(work);
  }
  state.SetLabel(lapack ? "LAPACK dpbtrf" : "ours");
}

void BM_BandedSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), b = static_cast<int>(state.range(1));
  const bool lapack = state.range(2) != 0;
  Banded m = banded(n, b);
  m.ours.factorize();
  LAPACKE_dpbtrf_work(LAPACK_COL_MAJOR, 'L', n, b, m.lapack.data(), b + 1);
  std::vector<double> x(n, 1.0);
  for (auto _ : state) {
    if (lapack)
      LAPACKE_dpbtrs_work(LAPACK_COL_MAJOR, 'L', n, b, 1, m.lapack.data(), b + 1, x.data(), n);
    else
      m.ours.solve(x.data());
    benchmark::DoNotOptimize(x.data());
  }
  state.SetLabel(lapack ? "LAPACK dpbtrs" : "ours");
}

// n, half-bandwidth, LAPACK (1) or ours (0).
void banded_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {1200, 6000})
    for (int band : {4, 8, 24})
      for (int lapack : {0, 1}) b->Args({n, band, lapack});
}
BENCHMARK(BM_BandedFactor)->Apply(banded_sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BandedSolve)->Apply(banded_sizes)->Unit(benchmark::kMicrosecond);

template <class T>
lapack_complex_double* as_lapack(T* p) {
  return reinterpret_cast<lapack_complex_double*>(p);
}

// One factor and one solve of a tridiagonal system of size n (the soils factor once per step
// size and solve every step, or factor once per frequency for the receptance).
template <class T>
void BM_Tridiagonal(benchmark::State& state) {
  using Vector = typename rumble::soils::TridiagonalLu<T>::Vector;
  const int n = static_cast<int>(state.range(0));
  const bool lapack = state.range(1) != 0;
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector diag(n), off(n - 1);
  for (int i = 0; i < n; ++i) diag[i] = T(2.0 + u(g));
  for (int i = 0; i + 1 < n; ++i) off[i] = T(u(g));
  rumble::soils::TridiagonalLu<T> ours;
  ours.resize(n);
  Vector d(n), dl(n - 1), du(n - 1), du2(n - 2), x = Vector::Ones(n);
  std::vector<lapack_int> pivots(n);
  for (auto _ : state) {
    if (lapack) {
      d = diag;
      dl = off;
      du = off;
      if constexpr (std::is_same_v<T, double>) {
        LAPACKE_dgttrf_work(n, dl.data(), d.data(), du.data(), du2.data(), pivots.data());
        LAPACKE_dgttrs_work(LAPACK_COL_MAJOR, 'N', n, 1, dl.data(), d.data(), du.data(), du2.data(),
                            pivots.data(), x.data(), n);
      } else {
        LAPACKE_zgttrf_work(n, as_lapack(dl.data()), as_lapack(d.data()), as_lapack(du.data()),
                            as_lapack(du2.data()), pivots.data());
        LAPACKE_zgttrs_work(LAPACK_COL_MAJOR, 'N', n, 1, as_lapack(dl.data()), as_lapack(d.data()),
                            as_lapack(du.data()), as_lapack(du2.data()), pivots.data(),
                            as_lapack(x.data()), n);
      }
    } else {
      ours.factor(diag, off);
      ours.solve(x);
    }
    benchmark::DoNotOptimize(x.data());
  }
  state.SetLabel(lapack ? "LAPACK ?gttrf + ?gttrs" : "ours");
}
void tridiagonal_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {100, 1000, 7000})
    for (int lapack : {0, 1}) b->Args({n, lapack});
}
BENCHMARK(BM_Tridiagonal<double>)->Apply(tridiagonal_sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tridiagonal<std::complex<double>>)
    ->Apply(tridiagonal_sizes)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
