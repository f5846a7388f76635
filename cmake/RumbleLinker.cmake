# The linker of the dev and asan presets (RUMBLE_LINKER=lld): LLVM's lld links the test
# executables about 4x as fast as GNU ld (fem_operator_tests: 0.34 s against 1.35 s with GCC,
# 0.58 s against 2.25 s with Clang and the sanitizers; 2026-12-06), a minute or two of the test
# command's wall time from a clean checkout (docs/toolchain.md §7). The release build and the
# installed SDK keep the system's linker: a plugin's build is its author's.
set(RUMBLE_LINKER "" CACHE STRING "linker for -fuse-ld= (empty: the compiler's default)")
if(RUMBLE_LINKER)
  add_link_options(-fuse-ld=${RUMBLE_LINKER})
endif()
