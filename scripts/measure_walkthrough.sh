#!/usr/bin/env bash
# The walkthrough modes on the animated Cornell box's 10-second fly-through (300 frames at 30 fps,
# 256x256): frames per second per mode and GL backend, and the error of every 10th frame against
# a converged render of the same instant (irad render --time t, N = 2048, the reference raster
# mode). Writes docs/data/walkthrough_modes.csv. Usage: bash scripts/measure_walkthrough.sh
set -euo pipefail
cd "$(dirname "$0")/.."
irad=build/bin/irad
scene=data/cornell_animated.gltf
out=out/walkthrough
csv=docs/data/walkthrough_modes.csv
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p "$out/ref" docs/data
step=10
for f in $(seq 0 $step 299); do # references, cached across runs
  ref="$out/ref/$f.exr"
  t=$(/usr/bin/python3 -c "print($f / 30)")
  [ -f "$ref" ] || "$irad" render "$scene" --time "$t" --size 256x256 --paths 2048 \
    --interleave 1 --quiet -o "$ref"
done
echo "mode,paths,gl,fps_rendering,mean_relmse,max_relmse" > "$csv"
run() { # mode paths gl
  local dir="$out/$1_$2_$3"
  mkdir -p "$dir"
  local line
  line=$("$irad" walkthrough "$scene" --frames 0:300 --fps 30 --size 256x256 --mode "$1" \
    --paths "$2" --gl "$3" -q -o "$dir/%04d.exr")
  local fps
  fps=$(echo "$line" | sed -E 's/.*: ([0-9.]+) frames\/s rendering.*/\1/')
  local errs=()
  for f in $(seq 0 $step 299); do
    "$irad" compare "$dir/$(printf %04d "$f").exr" "$out/ref/$f.exr" --json "$dir/cmp.json" > /dev/null
    errs+=("$(/usr/bin/python3 -c "import json; print(json.load(open('$dir/cmp.json'))['relmse'])")")
  done
  /usr/bin/python3 - "$1" "$2" "$3" "$fps" "${errs[@]}" >> "$csv" <<'PY'
import sys
mode, paths, gl, fps, *errs = sys.argv[1:]
e = [float(x) for x in errs]
print(f"{mode},{paths},{gl},{fps},{sum(e) / len(e):.4g},{max(e):.4g}")
PY
  tail -1 "$csv"
}
for gl in egl osmesa; do
  for mode in ring cached reshade; do run "$mode" 64 "$gl"; done
done
run ring 256 egl
run cached 16 egl
