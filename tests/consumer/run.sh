#!/bin/bash
# The installed package from outside: installs BUILD into a fresh prefix in a temporary folder,
# configures and builds tests/consumer against it (find_package(irad)), and runs the consumer on
# the Cornell box. Usage: run.sh CMAKE BUILD SOURCE.
set -euo pipefail
cmake_exe=$1 build=$2 source=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/irad_consumer.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$cmake_exe" --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/lib/cmake/irad/irad-config.cmake"
test -f "$work/prefix/lib/cmake/irad/irad-config-version.cmake"
test -f "$work/prefix/include/irad/irad.h"
"$cmake_exe" -S "$source/tests/consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" || {
  cat "$work/configure.log"
  exit 1
}
"$cmake_exe" --build "$work/build"
"$work/build/irad_consumer" "$source/data/cornell_box.gltf"
