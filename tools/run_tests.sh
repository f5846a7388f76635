#!/usr/bin/env bash
# The test job (also what CI runs): install what is missing, check formatting, build with
# warnings as errors and run the test suite, then build and run it again under ASan + UBSan
# with the fuzz targets (clang), each fuzzed for 20 s among the tests (docs/fuzzing.md).
#   tools/run_tests.sh            everything (from a clean checkout two full unity builds, each
#                                 target one translation unit: dev (GCC) about 23 CPU-minutes,
#                                 asan (Clang, the tests' own code at -O0, decision 0009, and
#                                 the five fuzz targets) 24, 12 minutes on 2 cores (2026-12-07);
#                                 the minutes of fuzzing packed with the sanitized tests, each
#                                 fuzzer on one core; later runs rebuild only what changed)
#   tools/run_tests.sh --quick    skip the sanitizer build and the fuzzing
# Tests labelled "validation" (long physics runs) are left out: ctest --preset dev -L validation.
# Each phase's wall time is printed at the end and kept in build/run_tests_times.txt, so a slow
# CI run says where its time went.
set -euo pipefail
cd "$(dirname "$0")/.."
times=()
phase() {  # phase NAME COMMAND...: run COMMAND, remember how long it took
  local name=$1 start=$SECONDS
  shift
  "$@"
  times+=("$(printf '%-14s %5d s' "$name" $((SECONDS - start)))")
}
report_times() {
  mkdir -p build
  printf '%s\n' "${times[@]}" "$(printf '%-14s %5d s' total "$SECONDS")" | tee build/run_tests_times.txt
}
trap report_times EXIT
jobs=$(nproc)
phase dependencies tools/install_dependencies.sh
phase format tools/check_format.sh
phase dev-build eval 'cmake --preset dev >/dev/null && cmake --build --preset dev -j"$jobs"'
phase dev-tests ctest --preset dev -j"$jobs" --timeout 300 -LE validation
if [ "${1:-}" != "--quick" ]; then
  phase asan-build eval 'cmake --preset asan >/dev/null && cmake --build --preset asan -j"$jobs"'
  phase asan-tests ctest --preset asan -j"$jobs" --timeout 600 -LE validation
fi
