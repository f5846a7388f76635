// advance() and motion() allocate nothing: every buffer is sized in accept_layout(). Counted by
// replacing malloc in this executable (glibc's documented way: the executable's malloc, calloc,
// realloc and free interpose for every library, the plugins included), delegating to glibc.
// Its own executable, so that no other test runs on the replaced allocator.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <nlohmann/json.hpp>

#include "soil_cases.hpp"
#include "soil_harness.hpp"

extern "C" {
void* __libc_malloc(std::size_t);  // NOLINT: glibc's own allocator
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
void count() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
void free(void* p) {
  __libc_free(p);
}
}

namespace rumble::test {
namespace {

/// Allocations during `steps` macro steps (quadratic waveform prepared beforehand) and motion.
long allocations_while_stepping(const std::string& type, const nlohmann::json& params) {
  constexpr Eigen::Index n = 31;
  TestSoil soil(type, params.dump());
  soil.accept_layout(sleeper_row(n));
  soil.initialize(VectorXd::Constant(n, 1e5));
  VectorXd coeff = VectorXd::Constant(3 * n, 1e3);
  coeff.head(n).setConstant(1e5);
  const rumble_waveform w{2, static_cast<std::uint64_t>(n), coeff.data()};
  VectorXd u(n), v(n);
  soil.api().advance(soil.self(), 0.0, 1e-3, &w);  // the first step factors K_eff (no alloc)
  allocations = 0;
  counting = true;
  for (int k = 1; k < 50; ++k) {
    soil.api().advance(soil.self(), k * 1e-3, 1e-3, &w);
    soil.api().motion(soil.self(), u.data(), v.data(), n);
  }
  counting = false;
  EXPECT_GT(u.norm(), 0.0);
  return allocations.load();
}

TEST(SoilAllocation, AdvanceAndMotionAllocateNothing) {
  EXPECT_EQ(allocations_while_stepping("winkler", soil_params(kSoils[1])), 0);
  EXPECT_EQ(allocations_while_stepping("clm", soil_params(kSoils[0])), 0);
  EXPECT_EQ(allocations_while_stepping(
                "clm", {{"m_f", 400.0}, {"k_f", 1e8}, {"c_f", 1e5}, {"k_c", 5e7}, {"c_c", 5e4}}),
            0);
}

TEST(SoilAllocation, TheCounterCounts) {
  // The test above can fail: an allocation in the counted window is seen.
  counting = true;
  allocations = 0;
  auto* p = new std::vector<double>(100);
  counting = false;
  delete p;
  EXPECT_GE(allocations.load(), 1);
}

}  // namespace
}  // namespace rumble::test
