#!/usr/bin/env bash
# ctest's gltf_validator: the Khronos glTF-Validator (scripts/validate_gltf.js, the npm package
# that scripts/setup.sh installs into build/npm) on data/*.gltf and on the files irad writes:
# the suite's irad::write_gltf round trips (kept through IRAD_GLTF_OUT, tests/keep_written_gltf.h)
# and `irad scene integrating-sphere|furnace-box|square-light`. Fails when any file has errors.
# Then, when the conformance files are there, checks that test_conformance.cpp's probe repairs
# nothing (tests/conformance_probe_check.js).
# Usage: bash tests/validate_written_gltf.sh IRAD IRAD_TESTS OUT_DIR NPM_DIR  (from the repo root)
set -euo pipefail
irad=$1 tests=$2 out=$3
export IRAD_NPM_DIR=$4

command -v node >/dev/null || { echo "gltf_validator: node not found (scripts/setup.sh)" >&2; exit 1; }
[ -d "$IRAD_NPM_DIR/node_modules/gltf-validator" ] || [ -n "${NODE_PATH:-}" ] ||
  { echo "gltf_validator: no $IRAD_NPM_DIR/node_modules/gltf-validator (scripts/setup.sh)" >&2
    exit 1; }

rm -rf "$out"
mkdir -p "$out"
IRAD_GLTF_OUT=$out "$tests" --gtest_brief=1 \
  --gtest_filter='AnalyticScenes.GltfRoundTrip*:Specular.LoaderThresholdsAndWriterRoundTrip'
for s in integrating-sphere furnace-box square-light; do
  "$irad" scene "$s" -o "$out/scene_$s.gltf" >/dev/null
done
node scripts/validate_gltf.js data/*.gltf "$out"/*.gltf

# The conformance test's probe repairs nothing: its probed copies keep their reports' errors.
suite=../shared/conformance/gltf-validator/test
if [ -d "$suite" ]; then
  IRAD_CONFORMANCE_OUT=$out/conformance "$tests" --gtest_brief=1 --gtest_filter='Conformance.Summary'
  node tests/conformance_probe_check.js "$suite" "$out/conformance"
fi
