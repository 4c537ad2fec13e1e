#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages only) and builds irad in Release into build/.
# Idempotent: installs nothing and rebuilds nothing when everything is in place.
# Usage: bash scripts/setup.sh        (as root, or with sudo available)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libembree-dev libosmesa6-dev libegl-dev libegl-mesa0 libgl-dev libglm-dev libopenexr-dev
  libstb-dev libdraco-dev libmeshoptimizer-dev libnanoflann-dev libwebp-dev nlohmann-json3-dev libgtest-dev libcli11-dev libfmt-dev libxxhash-dev
  python3-glad gnuplot-nox
  libglfw3-dev xvfb xauth # irad walkthrough --window, and its test under xvfb-run
  clang-14 libclang-rt-14-dev # the fuzzer: cmake --preset fuzz, fuzz/run.sh (libFuzzer, ASan)
  slurm-wlm munge # ctest slurm_array: a Slurm on localhost (tests/slurm/slurm_array.sh)
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-matplotlib # python/ (import irad)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# The Khronos glTF-Validator on the files we write (scripts/validate_gltf.js) runs on Node.js:
# Debian's nodejs and npm unless a node with npm is there already (another nodejs package, e.g.
# NodeSource's, which bundles npm and conflicts with Debian's npm).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  missing+=(nodejs npm)
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel "$(nproc)"

# The Khronos glTF-Validator (npm; only pre-releases of 2.0 are published, hence the exact
# version) for ctest's gltf_validator (scripts/validate_gltf.js). Needs the npm registry once.
if [ ! -d build/npm/node_modules/gltf-validator ]; then
  echo "setup: installing the npm package gltf-validator into build/npm" >&2
  npm install --prefix build/npm --no-audit --no-fund gltf-validator@2.0.0-dev.3.10
fi
