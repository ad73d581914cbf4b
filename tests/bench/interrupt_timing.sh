#!/bin/bash
# How fast Ctrl-C stops an MPI render (docs/reliability.md, "Nothing lost"). Starts
#   mpiexec -n 3 --oversubscribe prism render scenes/default.yaml -W 320 -H 180 --spp 64
#          --tile-size 16 --save-partial
# waits DELAY seconds, sends SIGINT either to rank 0 ("rank0") or to mpiexec ("mpiexec", what a
# terminal's Ctrl-C does), and prints the seconds until every rank is gone and until mpiexec
# has exited, its exit status and what was written. Usage:
#   tests/bench/interrupt_timing.sh [rank0|mpiexec] [TRIES] [build/prism]
set -u
mode=${1:-rank0}
tries=${2:-10}
prism=$(realpath "${3:-build/prism}")
scene=$(realpath "$(dirname "$0")/../../scenes/default.yaml")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
now() { date +%s.%N; }
for try in $(seq "$tries"); do
  rm -f "$work"/*
  mpiexec -n 3 --oversubscribe "$prism" render "$scene" -W 320 -H 180 --spp 64 --tile-size 16 \
    -o "$work/frame.png" --save-partial >"$work/log" 2>&1 &
  launcher=$!
  sleep "${DELAY:-3}"
  ranks=$(pgrep -P $launcher)
  rank0=""
  for pid in $ranks; do
    tr '\0' '\n' </proc/$pid/environ | grep -qx OMPI_COMM_WORLD_RANK=0 && rank0=$pid
  done
  if [ "$mode" = rank0 ]; then kill -INT "$rank0"; else kill -INT $launcher; fi
  start=$(now)
  for pid in $ranks; do  # gone, or a zombie waiting for mpiexec
    while [ -e /proc/$pid ] && ! grep -q '^State:.*Z' /proc/$pid/status 2>/dev/null; do
      sleep 0.005
    done
  done
  ranksGone=$(echo "$(now) - $start" | bc)
  wait $launcher
  status=$?
  launcherGone=$(echo "$(now) - $start" | bc)
  printf '%s try %2d: ranks gone %.3f s, mpiexec exited %.3f s, status %d, wrote %s %s\n' \
    "$mode" "$try" "$ranksGone" "$launcherGone" "$status" \
    "$(cd "$work" && ls frame* 2>/dev/null | tr '\n' ' ')" \
    "$(grep -o '[0-9]* of [0-9]* tiles' "$work/log")"
done
