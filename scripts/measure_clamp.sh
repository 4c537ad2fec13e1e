#!/usr/bin/env bash
# Measures the error of the raster against a converged path-traced reference on the Cornell box
# for a grid of paths N and global clamps (how the default --clamp is chosen; docs/accuracy.md).
# Usage: bash scripts/measure_clamp.sh [OUT_DIR] [SIZE] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/clamp}
size=${2:-128}
spp=${3:-16384}
irad=build/bin/irad
scene=data/cornell_box.gltf
mkdir -p "$out"
ref="$out/pt_${size}_${spp}.exr"
[ -f "$ref" ] || "$irad" render "$scene" -o "$ref" --estimator pt --spp "$spp" --size "${size}x${size}" --quiet
echo "paths,clamp,rmse,relmse,block8_rmse,raster_seconds"
for n in 64 128 256 512 1024; do
  for c in 0.01 0.02 0.03 0.05 0.07 0.1 0.15 0.2; do
    img="$out/raster_${n}_${c}.exr"
    "$irad" render "$scene" -o "$img" --paths "$n" --clamp-mode global --clamp "$c" \
      --size "${size}x${size}" --quiet \
      --stats "$out/stats.json"
    "$irad" compare "$img" "$ref" --json "$out/c1.json" > /dev/null
    "$irad" compare "$img" "$ref" --block 8 --json "$out/c8.json" > /dev/null
    /usr/bin/python3 - "$out" "$n" "$c" <<'PY'
import json, sys
out, n, c = sys.argv[1:4]
c1 = json.load(open(f"{out}/c1.json"))
c8 = json.load(open(f"{out}/c8.json"))
stats = json.load(open(f"{out}/stats.json"))
print(f"{n},{c},{c1['rmse']:.5f},{c1['relmse']:.6f},{c8['rmse']:.5f},{stats['seconds']['raster']:.3f}")
PY
  done
done
