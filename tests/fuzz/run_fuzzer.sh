#!/usr/bin/env bash
# The bounded fuzz run of the CTest test scenario_fuzz (CMakeLists.txt here):
#   run_fuzzer.sh FUZZER SCRATCH SECONDS DICT SEED_DIR...
# Fuzzes for SECONDS from the seed directories (read, never written) with the dictionary DICT;
# the inputs it finds go to SCRATCH/corpus, its log to SCRATCH/fuzz.log. Fails when libFuzzer
# stops on a crash, a leak, undefined behaviour, a broken property or an input slower than
# RUMBLE_FUZZ_TIMEOUT seconds (default 5); the input is kept in SCRATCH/artifacts and printed.
set -uo pipefail
fuzzer=$1 scratch=$2 seconds=$3 dict=$4
shift 4
rm -rf "$scratch"
mkdir -p "$scratch/corpus" "$scratch/artifacts"
# halt_on_error etc.: the first report stops the run; libFuzzer saves the input.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
"$fuzzer" -max_total_time="$seconds" -timeout="${RUMBLE_FUZZ_TIMEOUT:-5}" -rss_limit_mb=2048 \
  -max_len=16384 -dict="$dict" -artifact_prefix="$scratch/artifacts/" -print_final_stats=1 \
  -reload=0 "$scratch/corpus" "$@" >"$scratch/fuzz.log" 2>&1
rc=$?
# The seeds loaded, the last status lines and the final statistics (executions, coverage).
grep -E '^INFO: seed corpus|INITED' "$scratch/fuzz.log"
grep -E '^#[0-9]+' "$scratch/fuzz.log" | tail -n 3
grep -E '^stat::' "$scratch/fuzz.log"
shopt -s nullglob
artifacts=("$scratch"/artifacts/*)
if ((rc != 0 || ${#artifacts[@]})); then
  echo "scenario_fuzz FAILED (libFuzzer exit code $rc); the report:"
  grep -vE '^#[0-9]+|^INFO:' "$scratch/fuzz.log" | tail -n 60
  for a in "${artifacts[@]}"; do
    echo "--- input kept as $a ($(stat -c %s "$a") bytes), first 2 KiB:"
    head -c 2048 "$a" | cat -v
    echo
    echo "--- reproduce: $fuzzer $a"
  done
  exit 1
fi
echo "scenario_fuzz: no crash, leak, undefined behaviour, broken property or slow input"
