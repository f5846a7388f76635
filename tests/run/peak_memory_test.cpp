// Each phase's peak resident memory is its own (core/peak_memory.hpp): a phase that touches
// 64 MiB and frees them shows them, the phase after it, which touches nothing, does not. And
// freed memory goes back to the system even after a library told malloc to keep it
// (core/malloc_policy.hpp), so that a phase's peak is what it uses.
#include "core/peak_memory.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/malloc_policy.hpp"
#include "sanitizer.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

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

/// The process's resident memory now [bytes] (/proc/self/statm, in pages).
std::size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

/// The resident memory a block of 64 MiB leaves behind once touched and freed [bytes].
std::size_t left_by_a_freed_block() {
  // Through volatile pointers: the compiler may not drop an allocation it sees unused.
  void* (*volatile allocate)(std::size_t) = std::malloc;
  void* (*volatile fill)(void*, int, std::size_t) = std::memset;
  void (*volatile release)(void*) = std::free;
  const std::size_t before = resident_bytes();
  void* block = allocate(64 * kMiB);
  fill(block, 1, 64 * kMiB);
  release(block);
  const std::size_t after = resident_bytes();
  return after > before ? after - before : 0;
}

TEST(PeakMemory, FreedMemoryGoesBackAfterALibraryToldMallocToKeepIt) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "the malloc options are glibc's";
#else
  if (rumble::test::kUnderAddressSanitizer)
    GTEST_SKIP() << "a sanitizer's allocator keeps freed blocks";
  // What SuperLU_DIST's initialiser does when the FEM plugin loads it (with PETSc).
  ::mallopt(M_MMAP_MAX, 0);
  ::mallopt(M_TRIM_THRESHOLD, -1);
  const std::size_t kept = left_by_a_freed_block();
  EXPECT_GE(kept, 48 * kMiB) << "malloc gave the block back although told to keep it";
  rumble::return_freed_memory();
  rumble::trim_freed_memory();  // (what the kept block left: a phase's end does this)
  const std::size_t after_trim = resident_bytes();
  EXPECT_LT(left_by_a_freed_block(), 16 * kMiB);
  EXPECT_LT(resident_bytes(), after_trim + 16 * kMiB);
#endif
}

}  // namespace
