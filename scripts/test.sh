#!/usr/bin/env bash
# One command from a fresh clone: install what is missing, build, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --with-slurm  # Slurm and munge too, for the Slurm test
jobs=$(nproc 2>/dev/null || echo 2)
# The libFuzzer targets (clang-14, ASan + UBSan) in their own build dir: the suite runs each for a
# few seconds (FuzzShortRun.*). docs/reliability.md has the long runs.
[[ -f build-fuzz/CMakeCache.txt ]] || cmake --preset fuzz
cmake --build --preset fuzz -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs" --timeout 600
