#!/usr/bin/env bash
# The work of one frame, counted instead of timed: instructions and first-level data-cache read
# misses of `prism render` (one thread) under Cachegrind, the run at 2 samples per pixel less the
# run at 1, so start-up, scene and caustic-map builds and the image write cancel. The counts do
# not move with the machine's load, so changes of 1 % show, where wall-clock medians on a noisy
# 2-core machine need a 5 % change (docs/journal/2026-11-26-counting-a-frames-work.md). They are
# not times: confirm a kept change with alternating timed runs.
#   tests/bench/frame_cost.sh [--top N] PRISM [PRISM2 ...] [-- RENDER ARGS]
# RENDER ARGS default to the default scene at 320x180. For each binary: the frame's
# instructions, L1 data read misses, both per pixel, then its N costliest functions (default 15).
# Needs valgrind (Debian package `valgrind`); 10–20 s a binary at the default size.
set -euo pipefail
usage() {
  sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}
top=15
if [[ ${1:-} == --top ]]; then
  [[ ${2:-} =~ ^[0-9]+$ ]] || usage
  top=$2
  shift 2
fi
binaries=()
while (($#)) && [[ $1 != -- ]]; do
  binaries+=("$(realpath "$1")")
  shift
done
[[ ${1:-} == -- ]] && shift
((${#binaries[@]})) || usage
if ! command -v valgrind >/dev/null || ! command -v cg_annotate >/dev/null; then
  echo "frame_cost.sh: needs valgrind's cachegrind (apt-get install valgrind)" >&2
  exit 1
fi
repo=$(cd "$(dirname "$0")/../.." && pwd)
args=("$@")
((${#args[@]})) || args=("$repo/scenes/default.yaml" -W 320 -H 180)
# The image size, for the per-pixel figures: the last -W/-H given, else the scene's own (not
# known here: per-pixel figures are then left out).
width='' height=''
for ((i = 0; i < ${#args[@]} - 1; i++)); do
  case ${args[i]} in
    -W | --width) width=${args[i + 1]} ;;
    -H | --height) height=${args[i + 1]} ;;
  esac
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for prism in "${binaries[@]}"; do
  for spp in 1 2; do
    if ! valgrind --tool=cachegrind --cache-sim=yes --cachegrind-out-file="$out/cg.$spp" \
      "$prism" render "${args[@]}" --spp "$spp" --threads 1 -q --overwrite -o "$out/frame.exr" \
      >"$out/log" 2>&1; then
      echo "frame_cost.sh: $prism render failed:" >&2
      tail -5 "$out/log" >&2
      exit 1
    fi
  done
  cg_diff "$out/cg.1" "$out/cg.2" >"$out/frame.cg" 2>/dev/null
  cg_annotate --show=Ir,D1mr "$out/frame.cg" >"$out/annotated" 2>/dev/null
  # "INSTRUCTIONS (100.0%) MISSES (100.0%) PROGRAM TOTALS", numbers with thousands commas.
  read -r instructions misses < <(awk '/PROGRAM TOTALS/ {gsub(",", ""); print $1, $3; exit}' \
    "$out/annotated")
  echo "== $prism"
  awk -v ir="$instructions" -v d1="$misses" -v w="$width" -v h="$height" 'BEGIN {
    line = sprintf("frame: %.1f M instructions, %.3f M L1 data read misses", ir / 1e6, d1 / 1e6)
    if (w > 0 && h > 0) line = line sprintf(" (%.0f and %.2f per pixel)", ir / (w * h), d1 / (w * h))
    print line
  }'
  # The function rows: counts, then file:function; C++ signatures shortened to their names.
  awk '/file:function/ {rows = 1; next} rows && /^ *[0-9,]+ \(/ {print}' "$out/annotated" |
    sed -E 's/\?\?\?://; :a; s/\([^()]*\)//g; ta; s/ const//g;' |
    cut -c1-140 | head -n "$top"
done
