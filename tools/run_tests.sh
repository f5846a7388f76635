#!/usr/bin/env bash
# The test job (also what CI runs): install what is missing, check formatting, build with
# warnings as errors and run the test suite, then build and run it again under ASan + UBSan,
# then build the scenario fuzz target (clang) and fuzz for a minute (docs/fuzzing.md).
#   tools/run_tests.sh            everything (from a clean checkout two full unity builds: dev about
#                                 15 CPU-minutes, 30 without unity; asan more; the fuzz target
#                                 4.3 CPU-minutes and 60 s of fuzzing; later runs rebuild only
#                                 what changed)
#   tools/run_tests.sh --quick    skip the sanitizer builds (asan and fuzz)
# Tests labelled "validation" (long physics runs) are left out: ctest --preset dev -L validation.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_dependencies.sh
tools/check_format.sh
jobs=$(nproc)
cmake --preset dev >/dev/null
cmake --build --preset dev -j"$jobs"
ctest --preset dev -j"$jobs" --timeout 300 -LE validation
if [ "${1:-}" != "--quick" ]; then
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j"$jobs"
  ctest --preset asan -j"$jobs" --timeout 600 -LE validation
  cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz -j"$jobs"
  ctest --preset fuzz --timeout 600
fi
