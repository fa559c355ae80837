#!/usr/bin/env bash
# Runs each libFuzzer target (tests/fuzz) for SECONDS (default 30), as many at once as cores, from the
# committed seed corpus plus what earlier runs here found. Needs the sanitizer build
# (scripts/sanitizers.sh builds it in build-sanitize/). A crash, a sanitizer report, an input
# slower than 30 s or above 4 GiB fails the run and names the saved input; fix the bug and add
# the input to tests/fuzz/corpus/TARGET/.
#   bash scripts/fuzz.sh 600      (ten minutes per target)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
build="${COVERBENCH_SANITIZE_BUILD:-build-sanitize}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# One target a core at a time, each for SECONDS: the same fuzzing as one after another, in less time.
fuzz_one() {
  local target="$1" work="$build/fuzz/$1" start runs
  mkdir -p "$work/corpus" "$work/artifacts" "$work/tmp"
  start=$(date +%s)
  if ! TMPDIR="$work/tmp" "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 \
       -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" "tests/fuzz/corpus/$target" \
       > "$work/log.txt" 2>&1; then
    tail -n 40 "$work/log.txt"
    echo "fuzz: $target failed after $(( $(date +%s) - start )) s; input: $(ls -t "$work"/artifacts/* 2>/dev/null | head -1)" >&2
    return 1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log.txt" | grep -o '[0-9]*$')
  echo "fuzz: $target: $runs inputs in $(( $(date +%s) - start )) s, no crash"
}
targets=(wall_parser experiment_config plan_file planners serve)
at_once=$(nproc)
failed=0
for (( i = 0; i < ${#targets[@]}; i += at_once )); do
  pids=()
  for target in "${targets[@]:i:at_once}"; do
    fuzz_one "$target" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
done
exit "$failed"
