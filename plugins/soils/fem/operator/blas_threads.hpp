// The BLAS library's own threads beside the soil's (docs/toolchain.md §4). Debian's libblas.so.3
// is an alternative: OpenBLAS (its pthreads build) where installed, found here at run time. After
// every call it split over its threads, OpenBLAS's idle threads spin (sched_yield) for about
// 2^28 cycles before they sleep. PETSc's vector operations call BLAS every few milliseconds, so
// through the statics one BLAS thread spun on the second core the whole time: on one process at
// 1.0e6 DOFs, 14.8 s of CPU in a 33 s run, and beside busy processes the statics took
// 1.06-1.15x as long (bench/fem/MEASUREMENTS.md, "BLAS's threads"). The soil threads its own
// work (OpenMP); BLAS's threads pay only in the sparse factorisations (CHOLMOD's supernodes,
// UMFPACK's fronts), whose parallelism is all in BLAS: there they are let back in.
//
// The user's choice stands: with OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OPENBLAS_THREAD_TIMEOUT
// or GOTO_THREAD_TIMEOUT set, nothing here changes BLAS's threads.
#pragma once

namespace rumble::fem {

/// BLAS's thread count now, where it is OpenBLAS; 0 for another BLAS.
int blas_threads();

/// From now on BLAS runs on one thread outside a factorisation (BlasThreadsForFactorisation),
/// unless the user chose (above). Returns the threads a factorisation gets (BLAS's count at the
/// first call), or 0 where it changed nothing (another BLAS, or the user's choice). Call before
/// the soil's work, on the thread that creates the soil.
int keep_blas_on_one_thread();

/// For its lifetime BLAS may use the threads it had before keep_blas_on_one_thread (all the
/// cores, or none changed where it did nothing): around a sparse factorisation. (OpenBLAS's count
/// is one process-wide number; a BLAS call on another thread meanwhile, the track's under the
/// jacobi coupler, may split too.)
class BlasThreadsForFactorisation {
 public:
  BlasThreadsForFactorisation();
  ~BlasThreadsForFactorisation();
  BlasThreadsForFactorisation(const BlasThreadsForFactorisation&) = delete;
  BlasThreadsForFactorisation& operator=(const BlasThreadsForFactorisation&) = delete;

 private:
  bool raised_ = false;
};

}  // namespace rumble::fem
