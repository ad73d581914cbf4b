#!/usr/bin/env bash
# Uneven ranks, dynamic against static: one MPI job of two programs (MPMD), rank 0 with
# THREADS0 render threads and rank 1 with THREADS1, the same frame under both schedules in
# alternating rounds. Prints each run's render time and per-rank tiles and busy thread-seconds
# from Prism's run summary (docs/scaling.md, "Uneven ranks").
#   tests/bench/uneven_ranks.sh PRISM [ROUNDS (3)] [THREADS0 (1)] [THREADS1 (3)] [-- RENDER ARGS]
set -euo pipefail
prism=$(realpath "$1")
rounds=${2:-3}
threads0=${3:-1}
threads1=${4:-3}
shift $(($# < 4 ? $# : 4))
[[ ${1:-} == -- ]] && shift
repo=$(cd "$(dirname "$0")/../.." && pwd)
args=("$@")
((${#args[@]})) || args=("$repo/scenes/default.yaml" -W 640 -H 360 --spp 32 --tile-size 16)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # only needed as root
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "round schedule render_s rank0_tiles rank0_busy rank1_tiles rank1_busy"
for ((round = 1; round <= rounds; round++)); do
  for schedule in dynamic static; do
    common=(render "${args[@]}" --schedule "$schedule" --overwrite -o "$out/frame.exr")
    mpiexec --oversubscribe --bind-to none -n 1 "$prism" "${common[@]}" --threads "$threads0" \
      : -n 1 "$prism" "${common[@]}" --threads "$threads1" >"$out/log" 2>&1
    render=$(sed -n 's/^time      render \([0-9.]*\) s.*/\1/p' "$out/log")
    ranks=$(sed -n 's/^  rank [01]: [0-9]* threads, \([0-9]*\) tiles, .*busy \([0-9.]*\) thread-s.*/\1 \2/p' \
      "$out/log" | tr '\n' ' ')
    echo "$round $schedule $render $ranks"
  done
done
