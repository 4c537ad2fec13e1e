#!/usr/bin/env bash
# The raster stage (seconds.raster of `irad render --stats`) with each visibility (--visibility
# maps, rays, auto), the ray tracer's share of it (seconds.visibility), the whole render
# (seconds.total), the maps' shadow triangles per VPL and what was drawn (`visibility`), for each
# scene, every other option the default, SIZE x SIZE. The modes run in turn within each round, so
# a shared machine's load spreads over all of them alike; the scenes' shadow hierarchies are read
# from the cache (XDG_CACHE_HOME as set: run once before to fill it). Prints CSV rows;
# docs/performance.md "Visibility by rays" quotes them.
# Usage: LP_NUM_THREADS=2 bash scripts/measure_visibility.sh RUNS SIZE "maps rays auto" SCENE...
set -euo pipefail
runs=$1
size=$2
modes=$3
shift 3
irad=${IRAD:-build/bin/irad}
stats=$(mktemp --suffix=.json)
image=$(mktemp --suffix=.exr)
trap 'rm -f "$stats" "$image"' EXIT
echo "scene,visibility,run,drawn,seconds_raster,seconds_visibility,seconds_total,triangles_per_vpl"
for run in $(seq "$runs"); do
  for scene in "$@"; do
    for mode in $modes; do
      "$irad" render "$scene" --size "${size}x${size}" --visibility "$mode" --stats "$stats" \
        -o "$image" --quiet
      /usr/bin/python3 - "$stats" "$(basename "$scene")" "$mode" "$run" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
s = d["seconds"]
per_vpl = d["shadow_triangles"] / max(1, d["vpls"])
print(f"{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{d['visibility']},{s['raster']:.3f},"
      f"{s.get('visibility', 0.0):.3f},{s['total']:.3f},{per_vpl:.0f}")
PY
    done
  done
done
