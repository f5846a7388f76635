#!/usr/bin/env bash
# The bounded fuzz run of each CTest test <name>_fuzz (CMakeLists.txt here):
#   run_fuzzer.sh NAME FUZZER SCRATCH SECONDS DICT SEED_DIR...
# Fuzzes for SECONDS from the seed directories that exist (read, never written) with the dictionary DICT
# ("" for none); the inputs it finds go to SCRATCH/corpus, its log to SCRATCH/fuzz.log, and the
# files its checks write to SCRATCH/tmp ($TMPDIR). Fails when libFuzzer stops on a crash, a leak,
# undefined behaviour, a broken property or an input slower than RUMBLE_FUZZ_TIMEOUT seconds
# (default 5); the input is kept in SCRATCH/artifacts and printed. NAME names the run in messages.
set -uo pipefail
name=$1 fuzzer=$2 scratch=$3 seconds=$4 dict=$5
shift 5
rm -rf "$scratch"
mkdir -p "$scratch/corpus" "$scratch/artifacts" "$scratch/tmp"
# A check whose reader takes a path writes the input there (fuzz_support.hpp); an input that
# crashes leaves its files behind, in the scratch directory rather than /tmp.
export TMPDIR="$scratch/tmp"
# halt_on_error etc.: the first report stops the run; libFuzzer saves the input.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# gmsh (msh_fuzz) keeps a few blocks that gmsh::finalize does not free: third-party, suppressed
# as in the asan preset's tests (tests/lsan_suppressions.txt).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$(dirname "$0")/../lsan_suppressions.txt}"
dict_option=()
[ -n "$dict" ] && dict_option=(-dict="$dict")
seeds=()  # regressions/<name> is there once a defect was found
for d in "$@"; do [ -d "$d" ] && seeds+=("$d"); done
"$fuzzer" -max_total_time="$seconds" -timeout="${RUMBLE_FUZZ_TIMEOUT:-5}" -rss_limit_mb=2048 \
  -max_len=16384 "${dict_option[@]}" -artifact_prefix="$scratch/artifacts/" \
  -print_final_stats=1 -reload=0 "$scratch/corpus" "${seeds[@]}" >"$scratch/fuzz.log" 2>&1
rc=$?
# The seeds loaded, the last status lines and the final statistics (executions, coverage).
grep -E '^INFO: seed corpus|INITED' "$scratch/fuzz.log"
grep -E '^#[0-9]+' "$scratch/fuzz.log" | tail -n 3
grep -E '^stat::' "$scratch/fuzz.log"
shopt -s nullglob
artifacts=("$scratch"/artifacts/*)
if ((rc != 0 || ${#artifacts[@]})); then
  echo "$name FAILED (libFuzzer exit code $rc); the report:"
  grep -vE '^#[0-9]+|^INFO:' "$scratch/fuzz.log" | tail -n 60
  for a in "${artifacts[@]}"; do
    echo "--- input kept as $a ($(stat -c %s "$a") bytes), first 2 KiB:"
    head -c 2048 "$a" | cat -v
    echo
    echo "--- reproduce: $fuzzer $a"
  done
  exit 1
fi
echo "$name: no crash, leak, undefined behaviour, broken property or slow input"
