// Counts heap allocations in a window: for "no allocation per step" tests. Linking
// allocation_counter.cpp replaces malloc, calloc, realloc and the aligned allocators
// (aligned_alloc, memalign, posix_memalign) in the executable (glibc's documented
// way: the executable's definitions interpose for every library, dlopen'ed plugins included),
// delegating to glibc. Give such a test its own executable, so no other test runs on it, and do
// not build it under sanitizers, which replace malloc themselves.
#pragma once

namespace rumble::testing {

/// Allocations (operator new included, which allocates through malloc) while it lives.
class AllocationCounter {
 public:
  AllocationCounter();   // starts counting from 0
  ~AllocationCounter();  // stops
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  long count() const;
};

}  // namespace rumble::testing
