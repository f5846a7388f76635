// Each phase's peak resident memory is its own (core/peak_memory.hpp): a phase that touches
// 64 MiB and frees them shows them, the phase after it, which touches nothing, does not.
#include "core/peak_memory.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstring>

namespace {

constexpr std::size_t kMiB = 1024 * 1024;

TEST(PeakMemory, EachPhaseHasItsOwnPeak) {
  rumble::PhasePeaks memory;
  memory.end("before");
  {
    // Mapped and unmapped directly: a sanitizer's allocator would keep a freed block resident.
    const std::size_t n = 64 * kMiB;
    void* block = ::mmap(nullptr, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(block, MAP_FAILED);
    std::memset(block, 1, n);  // resident, not only reserved
    ::munmap(block, n);        // gone: the peak remains
  }
  memory.end("big");
  memory.end("small");
  const auto& p = memory.peaks();
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[1].first, "big");
  ASSERT_GT(p[0].second, 0u) << "/proc/self/status gave no VmHWM";
  EXPECT_GE(p[1].second, 64 * kMiB);
  if (!memory.separate()) GTEST_SKIP() << "this system does not let a process restart its peak";
  EXPECT_LT(p[2].second + 48 * kMiB, p[1].second) << "the phase after the block shows it";
}

}  // namespace
