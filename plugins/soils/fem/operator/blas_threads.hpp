// The BLAS library's own threads beside the soil's (docs/toolchain.md §4). Debian's libblas.so.3
// is an alternative: OpenBLAS (its pthreads build) where installed, found here at run time. After
// every call it split over its threads, OpenBLAS's idle threads spin (sched_yield) for about
// 2^28 cycles before they sleep. PETSc's vector operations call BLAS every few milliseconds, so
// through the statics one BLAS thread spun on the second core the whole time: on one process at
// 1.0e6 DOFs, 14.8 s of CPU in a 33 s run, and beside busy processes the statics took
// 1.06-1.15x as long. Nor did its threads pay where they were meant to: CHOLMOD's factor (the
// statics' and the implicit step's) took 1.3-1.6x as long on two of them as on one (1.1e5 and
// 2.4e5 DOFs; bench/fem/MEASUREMENTS.md, "BLAS's threads"). The soil threads its own work
// (OpenMP), and BLAS gets one thread.
//
// The user's choice stands: with OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OPENBLAS_THREAD_TIMEOUT
// or GOTO_THREAD_TIMEOUT set, nothing here changes BLAS's threads (on a machine with many cores
// and bigger factors, OPENBLAS_NUM_THREADS gives CHOLMOD more).
#pragma once

namespace rumble::fem {

/// The environment variables by which a user chooses OpenBLAS's threads (read when it loads).
inline constexpr const char* kBlasThreadChoices[] = {
    "OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OPENBLAS_THREAD_TIMEOUT", "GOTO_THREAD_TIMEOUT"};

/// BLAS's thread count now, where it is OpenBLAS; 0 for another BLAS.
int blas_threads();

/// From now on BLAS runs on one thread, unless the user chose (above). Returns the count it had
/// at the first call, or 0 where it changed nothing (another BLAS, or the user's choice). Call
/// before the soil's work, on the thread that creates the soil.
int keep_blas_on_one_thread();

}  // namespace rumble::fem
