#!/usr/bin/env bash
# Installs the Debian packages Prism needs (only those missing), then configures and builds
# Prism in Release mode into ./build. Safe to run again: it only does what is left to do.
# Usage: setup.sh [--with-slurm] [TARGET...]   (default: everything, tests included; demo.sh
# asks for `prism`, which brings the modules it loads)
#   --with-slurm  also install Slurm and munge for the Slurm test (test.sh passes it), as root
#                 only (the test needs root). Not on the demo path: on a machine with systemd,
#                 Debian enables and starts these packages' daemons.
set -euo pipefail
cd "$(dirname "$0")/.."

with_slurm=0
if [[ ${1:-} == --with-slurm ]]; then
  with_slurm=1
  shift
fi

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  libglm-dev libyaml-cpp-dev                      # renderer core: math, scenes
  libpng-dev libopenexr-dev                       # PNG and EXR, written on every render
  libjpeg62-turbo-dev                             # JPEG textures (models bring them)
  libsimdjson-dev                                 # glTF models: their JSON
  libopenimageio-dev                              # other image formats (loaded on first use)
  libcli11-dev                                    # command line
  libnanoflann-dev                                # k-nearest photons (caustics)
  libopenmpi-dev openmpi-bin                      # distribution over MPI
  libzstd-dev libsodium-dev                       # the remote viewer: frames, access token
  qtbase5-dev libqt5charts5-dev                   # the viewer (prism view)
  libgtest-dev                                    # tests
  libembree-dev                                   # ray-throughput yardstick (benchmark only)
  assimp-testmodels                               # public glTF test models (GltfPublicModels)
  clang-14 libclang-rt-14-dev                     # fuzzers: libFuzzer, sanitizers (test.sh)
)
if ((with_slurm)) && [[ $(id -u) -eq 0 ]]; then
  # The Slurm test's private cluster (tests/slurm/slurm_render.sh): controller, node daemon,
  # srun/sbatch and munge; Slurm's pmix plugin dlopens the unversioned libpmix.so of libpmix-dev.
  packages+=(slurm-wlm munge libpmix-dev)
elif ((with_slurm)); then
  echo "setup: not root, so the Slurm test will be skipped: Slurm and munge not installed"
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [[ $(id -u) -eq 0 ]]; then
    apt_get=(apt-get)
  elif command -v sudo >/dev/null; then
    apt_get=(sudo apt-get)
  else
    echo "setup: missing packages and no root or sudo: apt-get install ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${apt_get[@]}" update -qq
  "${apt_get[@]}" install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
if (($# > 0)); then
  cmake --build build -j "$jobs" --target "$@"
else
  cmake --build build -j "$jobs"
fi
