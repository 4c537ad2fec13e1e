#!/usr/bin/env bash
# Error against time on the Cornell box at SIZE^2 (docs/performance.md): the raster (k = 4, the
# default batch; with --bias-compensation; and --batch 1) over N paths, and the path tracer over
# spp, each timed by `irad render --stats` and scored by `irad compare` against a REFERENCE_SPP
# path-traced reference. Prints CSV. seconds: load + walk + raster (+ compensation) for the
# raster, load + trace for pt; not the clamped-fraction estimate --stats adds (a diagnostic that
# traces a ray per pixel and VPL).
# Usage: bash scripts/measure_equal_error.sh [OUT_DIR] [SIZE] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/equal_error}
size=${2:-512}
spp=${3:-4096}
irad=build/bin/irad
scene=data/cornell_box.gltf
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p "$out"
ref="$out/pt_${size}_${spp}.exr"
[ -f "$ref" ] || "$irad" render "$scene" -o "$ref" --estimator pt --spp "$spp" \
  --size "${size}x${size}" --quiet
run() { # name setting n args...
  local name=$1 setting=$2 n=$3
  shift 3
  "$irad" render "$scene" -o "$out/$name.exr" --size "${size}x${size}" --stats "$out/$name.json" \
    --quiet --clusters 0 "$@"
  "$irad" compare "$out/$name.exr" "$ref" --json "$out/$name.cmp.json" > /dev/null
  /usr/bin/python3 - "$out/$name" "$setting" "$n" <<'PY'
import json, sys
base, setting, n = sys.argv[1:4]
s = json.load(open(base + ".json"))
c = json.load(open(base + ".cmp.json"))
t = s["seconds"]
seconds = sum(t.get(k, 0.0) for k in ("load", "walk", "raster", "trace", "compensation"))
print(f"{s['estimator']},{setting},{n},{seconds:.3f},{c['relmse']:.4e}")
PY
}
echo "estimator,setting,n,seconds,relmse"
for n in 64 256 1024 4096 16384; do
  run "raster_$n" "k=4" "$n" --paths "$n"
  # The compensation's gather costs ~20 ms per VPL here: 3 minutes at N = 4096, not run beyond.
  [ "$n" -le 4096 ] && run "raster_bc_$n" "k=4 bias-compensation" "$n" --paths "$n" --bias-compensation
  run "raster_batch1_$n" "k=4 batch=1" "$n" --paths "$n" --batch 1
done
for s in 4 16 64 256; do
  run "pt_$s" "spp" "$s" --estimator pt --spp "$s"
done
