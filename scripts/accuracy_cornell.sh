#!/usr/bin/env bash
# The Cornell box at 256x256 with every estimator, against a converged path-traced reference:
# the images, error images and numbers in docs/accuracy.md. Usage: bash scripts/accuracy_cornell.sh
set -euo pipefail
cd "$(dirname "$0")/.."
irad=build/bin/irad
scene=data/cornell_box.gltf
out=out/accuracy
img=docs/images
mkdir -p "$out" "$img"
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
ref="$out/cornell_pt_256_8192.exr"
[ -f "$ref" ] || "$irad" render "$scene" -o "$ref" --estimator pt --spp 8192 --size 256x256 \
  --quiet --stats "$out/cornell_pt_256_8192.json"
"$irad" convert "$ref" -o "$img/cornell_reference_pt8192.png"
render() { # name, then render options
  local name=$1; shift
  "$irad" render "$scene" -o "$out/$name.exr" -o "$img/cornell_$name.png" --size 256x256 --quiet \
    --stats "$out/$name.json" "$@"
  "$irad" compare "$out/$name.exr" "$ref" --json "$out/$name.vs_pt.json" \
    --diff "$img/cornell_${name}_error.png" > /dev/null
}
render raster_256 --paths 256
render raster_k1_256 --paths 256 --interleave 1
render rtvpl_256 --paths 256 --estimator rt-vpl
render raster_1024 --paths 1024
render raster_1024_bc --paths 1024 --bias-compensation
render pt_64 --estimator pt --spp 64
render pt_256 --estimator pt --spp 256
# Shadow-map error alone: the reference raster mode (every VPL shades every pixel) against rt-vpl.
"$irad" compare "$out/raster_k1_256.exr" "$out/rtvpl_256.exr" --json "$out/raster_vs_rtvpl.json" \
  --diff "$img/cornell_raster_vs_rtvpl_error.png" --diff-max 0.05 > /dev/null
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
print("| image | seconds (total) | seconds (raster or trace) | relMSE vs pt 8192 spp | RMSE | mean ratio |")
print("| --- | --- | --- | --- | --- | --- |")
for name in ["raster_256", "raster_k1_256", "rtvpl_256", "raster_1024", "raster_1024_bc", "pt_64",
             "pt_256"]:
    s = json.load(open(f"{out}/{name}.json"))
    c = json.load(open(f"{out}/{name}.vs_pt.json"))
    ratio = sum(c["mean_ratio"]) / 3
    stage = s["seconds"].get("raster", s["seconds"].get("trace", 0.0))
    print(f"| {name} | {s['seconds']['total']:.2f} | {stage:.2f} | {c['relmse']:.3e} | {c['rmse']:.4f} | {ratio:.4f} |")
c = json.load(open(f"{out}/raster_vs_rtvpl.json"))
print(f"\nraster (interleave 1) vs rt-vpl (same 256 paths): relMSE {c['relmse']:.3e}, RMSE {c['rmse']:.5f}, "
      f"max {c['max_abs_error']:.4f}")
PY
