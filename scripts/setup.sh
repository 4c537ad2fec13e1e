#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages only) and builds irad in Release into build/.
# Idempotent: installs nothing and rebuilds nothing when everything is in place.
# Usage: bash scripts/setup.sh        (as root, or with sudo available)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libosmesa6-dev libegl-dev libegl-mesa0 libgl-dev libglm-dev libopenexr-dev
  libstb-dev libdraco-dev libmeshoptimizer-dev libwebp-dev nlohmann-json3-dev libgtest-dev libcli11-dev libfmt-dev
  python3-glad gnuplot-nox
  libglfw3-dev xvfb xauth # irad walkthrough --window, and its test under xvfb-run
  clang-14 libclang-rt-14-dev # the fuzzer: cmake --preset fuzz, fuzz/run.sh (libFuzzer, ASan)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
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
