// Whether this test binary is built with AddressSanitizer, whose shadow memory and quarantine
// count in the process's resident memory and whose allocator keeps freed blocks and ignores
// mallopt: tests that measure resident memory skip under it. GCC says so by
// __SANITIZE_ADDRESS__, Clang (the asan preset's compiler) by __has_feature.
#pragma once

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

}  // namespace rumble::test
