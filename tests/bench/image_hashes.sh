#!/usr/bin/env bash
# Renders every example scene and every SPD file with PRISM in one process and under mpirun, and
# prints one pixel hash per image (build/tests/prism_pixel_hash). A change to tracing,
# scheduling or transport must leave every hash as it was, and each scene's hashes equal across
# rank counts: run it with the old and the new binary and compare the two lists.
#   tests/bench/image_hashes.sh PRISM OUTDIR [RANKS (default 3)] [WIDTH HEIGHT (default 256 192)]
set -euo pipefail
if (($# < 2)); then
  sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
repo=$(cd "$(dirname "$0")/../.." && pwd)
prism=$(realpath "$1")
out=$2
ranks=${3:-3}
width=${4:-256}
height=${5:-192}
hasher=${PRISM_PIXEL_HASH:-$repo/build/tests/prism_pixel_hash}
spd=${PRISM_SPD_DIR:-$repo/../shared/scenes/spd}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # only needed as root
mkdir -p "$out"
scenes=("$repo"/scenes/*.yaml)
[[ -d $spd ]] && scenes+=("$spd"/*.nff)
for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.*}")
  "$prism" render "$scene" -W "$width" -H "$height" -q --overwrite -o "$out/$name-1.exr"
  mpirun --oversubscribe -np "$ranks" "$prism" render "$scene" -W "$width" -H "$height" -q \
    --overwrite -o "$out/$name-$ranks.exr"
done
"$hasher" "$out"/*.exr | tee "$out/hashes.txt"
# Each scene's images must agree across rank counts.
awk '{ name = $3; sub(/.*\//, "", name); sub(/-[0-9]+\.exr$/, "", name); print name, $1 }' \
  "$out/hashes.txt" | sort -u | awk '{ n[$1]++ } END { bad = 0; for (s in n) if (n[s] > 1) {
    print "DIFFERENT across rank counts: " s; bad = 1 } exit bad }'
