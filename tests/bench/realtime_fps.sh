#!/usr/bin/env bash
# The viewer's real-time frame rate (docs/viewer.md, "Real-time speed"): `prism view
# --benchmark-moves` in alternating rounds over variants, each printing its `realtime` line;
# then the median of each column per variant. Headless (QT_QPA_PLATFORM=offscreen).
#   tests/bench/realtime_fps.sh PRISM [ROUNDS (3)] [-- VIEW ARGS]
# Variants: 1 process with 2 threads; 2 ranks with 1 thread each, bound to a core each
# (mpiexec --bind-to core); each pipelined and with --no-pipeline. VIEW ARGS default to the
# default scene at 640x360, 1 spp, every frame at full resolution (--frame-time 0).
set -euo pipefail
prism=$(realpath "$1")
rounds=${2:-3}
shift $(($# < 2 ? $# : 2))
[[ ${1:-} == -- ]] && shift
repo=$(cd "$(dirname "$0")/../.." && pwd)
args=("$@")
((${#args[@]})) || args=("$repo/scenes/default.yaml" -W 640 -H 360 --spp 1 --frame-time 0)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # only needed as root
export QT_QPA_PLATFORM=offscreen
moves=(--benchmark-moves 200 --benchmark-interval 10)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {  # NAME COMMAND...: one run, its realtime line parsed into a row
  local name=$1
  shift
  if ! "$@" >"$out/log" 2>&1; then
    echo "$name failed:" >&2
    tail -5 "$out/log" >&2
    return 1
  fi
  sed -n "s/^realtime  \([0-9.]*\) frames\/s at \([0-9x]*\), frame time median \([0-9.]*\) ms, p95 \([0-9.]*\) ms, \([0-9]*\) frames at full resolution, \([0-9.]*\) Mrays\/s/$name \1 \3 \4 \5 \6/p" \
    "$out/log" | tee -a "$out/rows"
}
echo "variant fps median_ms p95_ms full_res_frames mrays_per_s"
for ((round = 1; round <= rounds; round++)); do
  run 1x2 "$prism" view "${args[@]}" --threads 2 "${moves[@]}"
  run 1x2-nopipe "$prism" view "${args[@]}" --threads 2 --no-pipeline "${moves[@]}"
  run 2x1 mpiexec --bind-to core -n 2 "$prism" view "${args[@]}" --threads 1 "${moves[@]}"
  run 2x1-nopipe mpiexec --bind-to core -n 2 "$prism" view "${args[@]}" --threads 1 --no-pipeline \
    "${moves[@]}"
done
echo "# medians over $rounds rounds"
python3 - "$out/rows" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, *values = line.split()
    rows.setdefault(name, []).append([float(v) for v in values])
for name, runs in rows.items():
    medians = [statistics.median(column) for column in zip(*runs)]
    print(name, " ".join(f"{m:.1f}" for m in medians))
if "1x2" in rows and "2x1" in rows:
    one = statistics.median(r[0] for r in rows["1x2"])
    two = statistics.median(r[0] for r in rows["2x1"])
    print(f"2x1 / 1x2 frames/s: {two / one:.2f}")
PY
