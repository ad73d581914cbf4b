#!/usr/bin/env bash
# Runs the libFuzzer targets (docs/reliability.md) for a given time each, one after another.
#
#   scripts/fuzz.sh [options] TARGET|all SECONDS
#     TARGET: yaml_scene, nff, obj, mtl, ply, gltf, glb, wire or view
#     --build-dir DIR  clang build with the fuzzers (default build-fuzz; configured and built with
#                      `cmake --preset fuzz` unless --no-build)
#     --work DIR       where the growing corpus, crash files and logs go (default DIR/fuzz-work)
#     --merge          afterwards, add the inputs that found new coverage to tests/fuzz/corpus/
#     --no-build       use the fuzzers as they are
#     --skip-missing   exit 77 (CTest's "skipped") when a fuzzer binary is missing
#
# Seeds: tests/fuzz/corpus/TARGET and tests/fuzz/regressions/TARGET (read only). Prints one line per
# target: seconds, executions, coverage (libFuzzer's cov: edges and ft: features), corpus size, and
# crash files. Exits 1 when any fuzzer found a crash, a leak, a timeout or ran out of memory; the
# input is saved under WORK/TARGET/ and belongs in tests/fuzz/regressions/TARGET once fixed.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build-fuzz
work=
merge=0
build=1
skip_missing=0
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --build-dir) build_dir=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --merge) merge=1; shift ;;
    --no-build) build=0; shift ;;
    --skip-missing) skip_missing=1; shift ;;
    *) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [[ $# -ne 2 ]]; then
  sed -n '4,12p' "$0" >&2
  exit 2
fi
all_targets=(yaml_scene nff obj mtl ply gltf glb wire view)
if [[ $1 == all ]]; then targets=("${all_targets[@]}"); else targets=("$1"); fi
seconds=$2
work=${work:-$build_dir/fuzz-work}

if ((build)); then
  if [[ $build_dir == build-fuzz ]]; then
    [[ -f build-fuzz/CMakeCache.txt ]] || cmake --preset fuzz >/dev/null
  fi
  cmake --build "$build_dir" --target prism_fuzzers
fi

status=0
printf '%-11s %8s %12s %6s %7s %7s %8s\n' target seconds executions cov ft corpus crashes
for t in "${targets[@]}"; do
  fuzzer=$build_dir/tests/fuzz/prism_fuzz_$t
  if [[ ! -x $fuzzer ]]; then
    echo "fuzz.sh: no fuzzer $fuzzer (build it with: cmake --preset fuzz && cmake --build --preset fuzz)" >&2
    if ((skip_missing)); then exit 77; fi
    exit 1
  fi
  dir=$work/$t
  rm -rf "$dir/crashes"  # the previous run's findings; copy them out before running again
  mkdir -p "$dir/corpus" "$dir/crashes" tests/fuzz/regressions/"$t"
  log=$dir/fuzz.log
  # -timeout: one input taking 10 s is a hang. -rss_limit_mb: past 2 GB is a finding too.
  # Seeds up to 64 KiB, so the bigger example meshes and NFF scenes are read whole.
  rc=0
  "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$dir/crashes/" \
    "$dir/corpus" tests/fuzz/corpus/"$t" tests/fuzz/regressions/"$t" >"$log" 2>&1 || rc=$?
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  corpus=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  crashes=$(find "$dir/crashes" -type f | wc -l)
  printf '%-11s %8s %12s %6s %7s %7s %8s\n' "$t" "$seconds" "${executions:-?}" "${cov:-?}" \
    "${ft:-?}" "${corpus:-?}" "$crashes"
  # LeakSanitizer's own tracer sometimes faults in its check at exit (under load, with threads
  # ending): the runtime failed, not the code, and libFuzzer blames the last input. Such a run
  # counts as clean only if every input it left replays clean, leak check included.
  if ((rc != 0)) && grep -q 'LeakSanitizer has encountered a fatal error' "$log"; then
    replayed=1
    for input in "$dir"/crashes/*; do
      [[ -f $input ]] || continue
      "$fuzzer" "$input" >>"$dir/replay.log" 2>&1 || replayed=0
    done
    if ((replayed)); then
      echo "fuzz.sh: $t: LeakSanitizer's tracer failed at exit, not a finding: $crashes" \
        "input(s) replay clean (log $log)" >&2
      continue
    fi
  fi
  if ((rc != 0 || crashes > 0)); then
    echo "fuzz.sh: $t failed (exit $rc); log $log, inputs in $dir/crashes:" >&2
    grep -m1 -A25 -E '^==[0-9]+==|runtime error|uncaught|terminate called' "$log" >&2 || tail -30 "$log" >&2
    status=1
  elif ((merge)); then
    # Only inputs that add coverage are kept, so the committed corpus stays small.
    "$fuzzer" -merge=1 -max_len=65536 tests/fuzz/corpus/"$t" "$dir/corpus" >"$dir/merge.log" 2>&1
  fi
done
exit $status
