#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time from a fresh corpus seeded with SEED_DIRs, and
# fails on any crash, leak, timeout (10 s per input) or out-of-memory (2 GiB). The log and any
# crashing input stay in WORKDIR; the number of executions is printed for the CI log.
#
#   run_fuzzer.sh FUZZER SECONDS WORKDIR SEED_DIR...
set -euo pipefail
fuzzer=$1 seconds=$2 work=$3
shift 3
rm -rf "$work"
mkdir -p "$work/corpus" "$work/cwd"
# An empty working directory: a fuzzed `mesh` line finds no file here.
cd "$work/cwd"
status=0
# A fixed seed (RAYLANE_FUZZ_SEED, default 1) makes a run a prefix of one reproducible
# sequence: CI explores what a longer run on a developer's machine already explored, so what
# lands is what was checked. RAYLANE_FUZZ_SEED=0 lets libFuzzer pick one (new ground).
"$fuzzer" -seed="${RAYLANE_FUZZ_SEED:-1}" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/" "$work/corpus" "$@" >"$work/log" 2>&1 || status=$?
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || true)
echo "$(basename "$fuzzer"): ${runs:-?} executions in ${seconds} s, exit status $status" |
  tee "$work/summary"
if [ "$status" -ne 0 ]; then
  tail -n 60 "$work/log"
  ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null || true
fi
exit "$status"
