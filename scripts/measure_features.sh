#!/usr/bin/env bash
# "Only what the scene needs": a diffuse-only scene (the Cornell box: no texture, no mirror, no
# punctual or directional light, no animation) renders in the same time with this build as with
# OLD_IRAD, a build without the extensions jitter, mirrors, directional lights, light allocation
# and animation (both have textures). Alternates the two binaries, 7 runs each,
# and prints the medians of seconds.raster and seconds.total from --stats.
# Usage: bash scripts/measure_features.sh OLD_IRAD [NEW_IRAD]   (writes docs/data/features.csv)
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=${2:-build/bin/irad}
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
csv=docs/data/features.csv
echo "binary,run,size,estimator,seconds_raster,seconds_total,vpls" > "$csv"
for run in 1 2 3 4 5 6 7; do
  for which in old new; do
    bin=$old
    [ "$which" = new ] && bin=$new
    for est in raster rt-vpl; do
      "$bin" render data/cornell_box.gltf --size 512x512 --estimator "$est" --quiet \
        -o "$tmp/x.exr" --stats "$tmp/s.json"
      /usr/bin/python3 - "$tmp/s.json" "$which" "$run" "$est" >> "$csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
sec = s["seconds"]
print(f"{sys.argv[2]},{sys.argv[3]},512,{sys.argv[4]},{sec.get('raster', sec.get('trace', 0))},{sec['total']},{s['vpls']}")
PY
    done
  done
done
/usr/bin/python3 - "$csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| estimator | build | median seconds (raster or trace) | median seconds total | VPLs |")
print("| --- | --- | --- | --- | --- |")
for est in ("raster", "rt-vpl"):
    for b in ("old", "new"):
        r = [x for x in rows if x["binary"] == b and x["estimator"] == est]
        print(f"| {est} | {b} | {statistics.median(float(x['seconds_raster']) for x in r):.3f} | "
              f"{statistics.median(float(x['seconds_total']) for x in r):.3f} | {r[0]['vpls']} |")
PY
