#!/usr/bin/env bash
# Runs every libFuzzer target (or those named) for SECONDS each on its corpus in fuzz/corpus/,
# two at a time. New inputs go to build-asan/fuzz-new/<target>, never into the committed corpus;
# a crash, sanitizer report, timeout (60 s per input) or allocation over 2 GB fails the script
# and leaves the input in build-asan/fuzz-artifacts/. Usage: scripts/fuzz.sh [SECONDS] [target...]
# Needs the build from scripts/sanitize.sh (built here if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
((${#targets[@]})) || targets=(grain_file config cli history_db fit_points)
if [[ ! -x build-asan/fuzz/fuzz_${targets[0]} ]]; then
  bash scripts/sanitize.sh -R '^$' > /dev/null  # configure and build only
fi
export CCACHE_DIR="${CCACHE_DIR:-$PWD/.ccache}"
cmake --build build-asan -j "$(nproc)" > /dev/null
source scripts/sanitizer_env.sh
mkdir -p build-asan/fuzz-artifacts
run_one() {
  local t="$1" new="build-asan/fuzz-new/$1" log="build-asan/fuzz-$1.log"
  mkdir -p "$new"
  if ! build-asan/fuzz/fuzz_"$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix=build-asan/fuzz-artifacts/"$t"- \
      "$new" fuzz/corpus/"$t" > "$log" 2>&1; then
    echo "fuzz_$t: FAILED (log $log):" >&2
    grep -E 'ERROR|runtime error|Test unit written|SUMMARY' "$log" | head -20 >&2
    return 1
  fi
  echo "fuzz_$t: $(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}') executions in ${seconds} s," \
       "corpus $(grep -oE 'corp: [0-9]+/[0-9]+[a-zA-Z]*' "$log" | tail -1 | cut -d' ' -f2), $(grep -oE 'cov: [0-9]+' "$log" | tail -1)"
}
status=0
pids=()
for t in "${targets[@]}"; do
  run_one "$t" & pids+=($!)
  if ((${#pids[@]} >= $(nproc))); then wait "${pids[0]}" || status=1; pids=("${pids[@]:1}"); fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
exit $status
