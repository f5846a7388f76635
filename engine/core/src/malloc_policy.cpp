#include "core/malloc_policy.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rumble {

void return_freed_memory() {
#if defined(__GLIBC__)
  constexpr int kMmapThreshold = 32 << 20;  // bytes (glibc's DEFAULT_MMAP_THRESHOLD_MAX, 64-bit)
  constexpr int kMmapMax = 65536;           // glibc's default count of such mappings
  ::mallopt(M_MMAP_MAX, kMmapMax);
  ::mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
  ::mallopt(M_TRIM_THRESHOLD, 2 * kMmapThreshold);
#endif
}

bool trim_freed_memory() {
#if defined(__GLIBC__)
  return ::malloc_trim(0) != 0;
#else
  return false;
#endif
}

}  // namespace rumble
