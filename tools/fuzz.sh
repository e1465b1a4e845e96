#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/, FACESKETCH_FUZZ=ON, clang-14, ASan + UBSan) in
# build-fuzz/ and runs them, one per core at a time, each for SECONDS (default 30).
#   tools/fuzz.sh                    every target, 30 s each
#   tools/fuzz.sh ply 600            one target for 10 minutes
#   FUZZ_RUNS=1000000 tools/fuzz.sh model 1800   stop after a million executions (or 30 min)
#   FUZZ_JOBS=2 ...                  compile with 2 jobs (default: all cores)
#   FUZZ_PARALLEL=1 ...              run one target at a time (default: one per core)
#   FUZZ_SEED=1 ...                  libFuzzer's random seed (default: a new one per run); CI fixes
#                                    it so that a red run is reproducible and a green one stays green
# The working corpus grows in build-fuzz/corpus/<target> (seeded from tests/fuzz/<target>/);
# a crash, leak, timeout (10 s) or allocation over 1 GB stops the run and leaves its input in
# build-fuzz/crashes/<target>/, and the script fails. Keep each fixed crash's input as
# tests/fuzz/<target>/regress-<what>, which the test suite replays (tests/fuzz/replay.cpp).
# The last line per target is `fuzz TARGET: N runs, cov C, ft F` (libFuzzer's counters).
set -euo pipefail
cd "$(dirname "$0")/.."

targets=(obj obj_vertices ply manifest ict_json model curvature_cache png session pose_model feature_points)
what=${1:-all}
seconds=${2:-30}
[ "$what" = all ] || targets=("$what")

# A unity build (sources joined in batches of 8): 351 against 512 CPU s for every target, one file
# per compile (BENCHMARKS.md, "CI time"); the fuzzers run the same code either way.
cmake -S . -B build-fuzz -DFACESKETCH_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DFACESKETCH_WERROR=ON \
      -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build-fuzz -j"${FUZZ_JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}" >/dev/null

# Scratch files on tmpfs: every execution writes its input to a file, as the readers take paths.
[ -d /dev/shm ] && export TMPDIR=/dev/shm
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# One target per core at a time (FUZZ_PARALLEL, default: all cores): each libFuzzer process runs on
# one core, so on two cores CI's eleven 10-s runs take about a minute instead of two. Each target
# has its own corpus, log and crash folder; the summary lines print in the targets' order.
fuzz_one() {
  local t=$1
  local corpus=build-fuzz/corpus/$t crashes=build-fuzz/crashes/$t log=build-fuzz/fuzz-$t.log result line runs_done
  mkdir -p "$corpus" "$crashes"
  local runs=()
  [ -n "${FUZZ_RUNS:-}" ] && runs=(-runs="$FUZZ_RUNS")
  [ -n "${FUZZ_SEED:-}" ] && runs+=(-seed="$FUZZ_SEED")
  if nice -n 10 "build-fuzz/tests/fuzz/fuzz_$t" "$corpus" "tests/fuzz/$t" -max_total_time="$seconds" "${runs[@]}" \
       -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=16384 -print_final_stats=1 \
       -artifact_prefix="$crashes/" >"$log" 2>&1; then
    result=ok
  else
    result="FAILED (see $log and $crashes/)"
  fi
  # The last status line ("#N DONE cov: C ft: F ..." or the last "#N ... cov:" before a crash).
  line=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  runs_done=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+)/\1/p' "$log" | tail -1)
  echo "fuzz $t: ${runs_done:-${line%% *}} runs, cov $(sed -nE 's/.*cov: ([0-9]+).*/\1/p' <<<"$line"), ft $(sed -nE 's/.*ft: ([0-9]+).*/\1/p' <<<"$line"), $result" \
    >"build-fuzz/fuzz-$t.summary"
}
parallel=${FUZZ_PARALLEL:-$(nproc)}
running=0
for t in "${targets[@]}"; do
  rm -f "build-fuzz/fuzz-$t.summary"
  if [ "$running" -ge "$parallel" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
wait
status=0
for t in "${targets[@]}"; do
  if [ -f "build-fuzz/fuzz-$t.summary" ]; then
    cat "build-fuzz/fuzz-$t.summary"
    grep -q ', ok$' "build-fuzz/fuzz-$t.summary" || status=1
  else
    echo "fuzz $t: no summary (the run did not finish)"
    status=1
  fi
done
exit $status
