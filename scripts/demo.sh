#!/usr/bin/env bash
# One command from a fresh clone: install what is missing, build, render the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh prism  # the renderer and its modules; scripts/test.sh builds the tests
./build/prism render scenes/default.yaml -o default.png --overwrite  # a re-run replaces it
echo "demo: open default.png"
