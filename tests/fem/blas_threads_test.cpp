// BLAS's threads beside the soil's (operator/blas_threads.hpp): where BLAS is OpenBLAS, one
// thread, so that no BLAS thread spins on a core while the soil works; the user's OPENBLAS_*
// choice untouched. Skipped where libblas.so.3 is another BLAS (tools/install_dependencies.sh
// installs OpenBLAS).
#include "operator/blas_threads.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sched.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rumble::fem {
namespace {

// OpenBLAS's own thread count, read before any test can change it (whatever order they run in).
const int own_threads = blas_threads();

/// The user's OPENBLAS_* variables unset for the test, put back at its end.
class BlasThreads : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : kBlasThreadChoices)
      if (const char* v = std::getenv(name)) saved_.emplace_back(name, v);
    for (const char* name : kBlasThreadChoices) ::unsetenv(name);
    if (blas_threads() == 0) GTEST_SKIP() << "libblas.so.3 is not OpenBLAS here";
  }
  void TearDown() override {
    for (const auto& [name, value] : saved_) ::setenv(name.c_str(), value.c_str(), 1);
  }

 private:
  std::vector<std::pair<std::string, std::string>> saved_;
};

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// OpenBLAS's thread count set directly (for the control below).
void set_openblas_threads(int threads) {
  const auto set =
      reinterpret_cast<void (*)(int)>(::dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set == nullptr) throw std::runtime_error("no openblas_set_num_threads in the process");
  set(threads);
}

/// The process's CPU time [s] over 0.3 s of sleep.
double cpu_while_idle() {
  const double start = process_cpu_seconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  return process_cpu_seconds() - start;
}

/// The CPU time [s] that a thread which only yields (as OpenBLAS's idle ones do) gets in 0.1 s on
/// this machine now: next to none where every core is busy, as sched_yield gives the core away.
double cpu_of_a_yielding_thread() {
  double cpu = 0.0;
  std::thread yielding([&cpu] {
    timespec start{}, end{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &start);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    while (std::chrono::steady_clock::now() < until) sched_yield();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &end);
    cpu = static_cast<double>(end.tv_sec - start.tv_sec) +
          1e-9 * static_cast<double>(end.tv_nsec - start.tv_nsec);
  });
  yielding.join();
  return cpu;
}

/// The process's CPU time [s] over 0.3 s of sleep just after a 600 x 600 product by BLAS's dgemm
/// (split over BLAS's threads where it has more than one).
double cpu_while_idle_after_a_product() {
  using Dgemm = void (*)(const char*, const char*, const int*, const int*, const int*,
                         const double*, const double*, const int*, const double*, const int*,
                         const double*, double*, const int*);
  const auto dgemm = reinterpret_cast<Dgemm>(::dlsym(RTLD_DEFAULT, "dgemm_"));
  if (dgemm == nullptr) throw std::runtime_error("no dgemm_ in the process");
  const int n = 600;
  const double one = 1.0, zero = 0.0;
  std::vector<double> a(n * n, 0.5), b(n * n, 0.25), c(n * n, 0.0);
  dgemm("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n);
  return cpu_while_idle();
}

TEST_F(BlasThreads, OneThreadOnceTheSoilAsks) {
  ASSERT_EQ(keep_blas_on_one_thread(), own_threads);
  EXPECT_EQ(blas_threads(), 1);
  EXPECT_EQ(keep_blas_on_one_thread(), own_threads) << "a second soil reports the count it had";
  EXPECT_EQ(blas_threads(), 1);
}

TEST_F(BlasThreads, TheUsersChoiceStands) {
  for (const char* name : kBlasThreadChoices) {
    ::setenv(name, "2", 1);
    const int now = blas_threads();
    EXPECT_EQ(keep_blas_on_one_thread(), 0) << name;
    EXPECT_EQ(blas_threads(), now) << name;
    ::unsetenv(name);
  }
}

// The reason for it: after a product on two threads OpenBLAS's idle thread spins (sched_yield)
// for about 0.1 s, the process's CPU time growing while it sleeps (0.10 s of 0.3 here, alone on
// the machine); on one thread it does not (under 1 ms).
TEST_F(BlasThreads, NoBlasThreadSpinsAfterACall) {
  if (keep_blas_on_one_thread() < 2) GTEST_SKIP() << "OpenBLAS has one thread here: none spins";
  cpu_while_idle();  // (OpenBLAS's threads also spin for 0.1 s from the process's start)
  EXPECT_LT(cpu_while_idle_after_a_product(), 0.003);
  set_openblas_threads(own_threads);  // (the control: OpenBLAS's own threads spin)
  const double spun = cpu_while_idle_after_a_product();
  set_openblas_threads(1);
  if (cpu_of_a_yielding_thread() < 0.02)  // (beside two busy processes: 0.16 ms, not 100)
    GTEST_SKIP() << "every core is busy now: a yielding thread gets no CPU, so the control "
                    "cannot see OpenBLAS's spin (the check on one thread above holds)";
  EXPECT_GT(spun, 0.003);
}

}  // namespace
}  // namespace rumble::fem
