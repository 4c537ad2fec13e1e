#!/usr/bin/env bash
# The raster stage (seconds.raster of `irad render --stats`: set-up, shadow atlases, shading) and
# the whole render (seconds.total) for each scene and batch size (--batch), every other option
# the default, SIZE x SIZE. The batch sizes run in turn within each round, so a shared machine's
# load spreads over all of them alike; the scenes' shadow hierarchies are read from the cache
# (XDG_CACHE_HOME as set: run once before to fill it). Prints CSV rows; docs/performance.md
# "Batches" quotes the medians of docs/data/speed_batch_sizes_256.csv.
# Usage: LP_NUM_THREADS=2 bash scripts/measure_batch_sizes.sh RUNS SIZE "16 32 64" SCENE...
set -euo pipefail
runs=$1
size=$2
batches=$3
shift 3
irad=${IRAD:-build/bin/irad}
stats=$(mktemp --suffix=.json)
image=$(mktemp --suffix=.exr)
trap 'rm -f "$stats" "$image"' EXIT
echo "scene,batch,run,seconds_raster,seconds_total"
for run in $(seq "$runs"); do
  for scene in "$@"; do
    for batch in $batches; do
      "$irad" render "$scene" --size "${size}x${size}" --batch "$batch" --stats "$stats" \
        -o "$image" --quiet
      /usr/bin/python3 - "$stats" "$(basename "$scene")" "$batch" "$run" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["seconds"]
print(f"{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{s['raster']:.3f},{s['total']:.3f}")
PY
    done
  done
done
