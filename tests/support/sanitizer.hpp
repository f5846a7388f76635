// Whether this test binary is built with AddressSanitizer, whose shadow memory and quarantine
// count in the process's resident memory and whose allocator keeps freed blocks and ignores
// mallopt: tests that measure resident memory skip under it. GCC says so by
// __SANITIZE_ADDRESS__, Clang (the asan preset's compiler) by __has_feature.
//
// kSanitizedShare and RUMBLE_PHYSICS_IN_THE_DEV_BUILD_ONLY(): a long physics run (a load held
// 0.5 s, a steady state, thousands of steps for a growing mode) is cut to a tenth of its
// simulated time under AddressSanitizer, or run once where the dev build runs it at several
// steps or speeds, or on a coarser mesh, where it checks memory (every path of its step runs in
// the first steps), and returns before the physics that needs the whole run, which the dev
// build checks.
//
// RUMBLE_SKIP_STUDY_UNDER_ASAN(): a study that runs one code path at several sizes or steps (a
// convergence or energy series, seconds in the dev build, a minute under the sanitizers) is
// skipped under AddressSanitizer, where its suite's lighter tests run the same paths; the dev
// build runs it (docs/toolchain.md, "What runs under the sanitizers").
#pragma once

#include <cstdio>

namespace rumble::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

/// The share of a long physics run's simulated time this build runs (see above).
inline constexpr double kSanitizedShare = kUnderAddressSanitizer ? 0.1 : 1.0;

}  // namespace rumble::test

#define RUMBLE_PHYSICS_IN_THE_DEV_BUILD_ONLY()                                               \
  if (::rumble::test::kUnderAddressSanitizer) {                                              \
    std::printf(                                                                             \
        "[ sanitized ] a shorter or smaller run for memory; its physics is the dev build's " \
        "(tests/support/sanitizer.hpp)\n");                                                  \
    return;                                                                                  \
  }

#define RUMBLE_SKIP_STUDY_UNDER_ASAN()                                                     \
  if (::rumble::test::kUnderAddressSanitizer)                                              \
  GTEST_SKIP() << "a study of one code path at several sizes: under AddressSanitizer its " \
                  "suite's lighter tests run the same paths (tests/support/sanitizer.hpp)"
