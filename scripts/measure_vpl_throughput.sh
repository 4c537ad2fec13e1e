#!/usr/bin/env bash
# VPL throughput of the raster (vpls / seconds.raster of `irad render --stats`, which includes
# context creation, upload and shader compilation) on the Cornell box, as medians over RUNS runs.
# The configurations run in turn within each round, so a shared machine's load spreads over all
# of them alike (docs/performance.md).
# Usage: bash scripts/measure_vpl_throughput.sh [RUNS] [SIZE] [LABEL=BINARY:ARGS ...]
# Default configurations: --batch 1 (one pass per VPL) and the default batch, k = 4 and k = 1.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-9}
size=${2:-512}
shift $(($# < 2 ? $# : 2))
configs=("$@")
if [ ${#configs[@]} -eq 0 ]; then
  configs=("batch1=build/bin/irad:--batch 1" "default=build/bin/irad:"
           "batch1_k1=build/bin/irad:--batch 1 --interleave 1" "default_k1=build/bin/irad:--interleave 1")
fi
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
stats=$(mktemp --suffix=.json)
image=$(mktemp --suffix=.png)
trap 'rm -f "$stats" "$image"' EXIT
echo "config,run,vpls,seconds_raster,vpls_per_second"
for run in $(seq "$runs"); do
  for spec in "${configs[@]}"; do
    label=${spec%%=*}; rest=${spec#*=}; binary=${rest%%:*}; args=${rest#*:}
    # N = 256 fixed, not the light budget's (491 VPLs: every one drawn, k = 4 unless ARGS say).
    # shellcheck disable=SC2086
    "$binary" render data/cornell_box.gltf --size "${size}x${size}" --stats "$stats" -o "$image" \
      --quiet --paths 256 $args
    /usr/bin/python3 - "$stats" "$label" "$run" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]},{sys.argv[3]},{s['vpls']},{s['seconds']['raster']:.4f},"
      f"{s['vpls'] / s['seconds']['raster']:.1f}")
PY
  done
done
