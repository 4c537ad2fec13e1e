#!/usr/bin/env bash
# Regenerates the images of docs/environment.md (docs/images/env_*.png) from a shared third-party
# scene, MorphStressTest (Khronos sample model, CC BY 4.0, ../shared/scenes; read, never copied),
# lit by the synthetic studio map of scripts/make_studio_env.py and by Preetham's sky. 15 to 25 s
# on 2 shared cores with LP_NUM_THREADS=2 (MEASURE=1: about 4 minutes more). Every image is
# 256x160 per panel, panels side by side (scripts/side_by_side.py):
#   env_studio_estimators.png  studio map: raster (N = 256, interleave 4), rt-vpl (N = 256),
#                              pt (256 spp)
#   env_sky_elevations.png     --sky 10,70 / 30,70 / 60,70, raster, PNG at --exposure 0.5
#   env_default_white.png      no light options: the default white environment (prints its warning)
#   env_visible.png            studio map, raster: --env-visible on, then off
# With MEASURE=1 it also prints the timing and error table of the page: raster (interleave 4
# and 1), rt-vpl and pt (64, 256 spp) at 256x256, 3 runs each (median of --stats seconds), and
# each at 128x128 against a pt reference of REF_SPP (default 4096) spp.
# Usage: scripts/environment_docs.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
irad="${1:-build}/bin/irad"
scene=../shared/scenes/MorphStressTest/MorphStressTest.gltf
img=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export LP_NUM_THREADS=2
view=(--look-from "1.8,0.9,3.1" --look-at "0.3,0.2,0")
size=256x160
python3 scripts/make_studio_env.py "$tmp/studio.hdr" 1024
studio=(--env "$tmp/studio.hdr")
r() { "$irad" render "$scene" "${view[@]}" --size "$size" --quiet "$@"; }

# (a) the three estimators under the studio map
r "${studio[@]}" -o "$tmp/raster.png"
r "${studio[@]}" --estimator rt-vpl -o "$tmp/rtvpl.png"
r "${studio[@]}" --estimator pt --spp 256 -o "$tmp/pt.png"
python3 scripts/side_by_side.py "$img/env_studio_estimators.png" 1 "$tmp/raster.png" \
  "$tmp/rtvpl.png" "$tmp/pt.png"

# (b) the clear sky, sun 10, 30 and 60 degrees up at azimuth 70 (from +Z toward +X: to the right
# of the camera, which is at azimuth 30), one exposure for all three (+0.5 EV: at +1 the plate's
# top clips under the 60-degree sun)
for e in 10 30 60; do r --sky "$e,70" --exposure 0.5 -o "$tmp/sky$e.png"; done
python3 scripts/side_by_side.py "$img/env_sky_elevations.png" 1 "$tmp/sky10.png" \
  "$tmp/sky30.png" "$tmp/sky60.png"

# (c) no light options: the scene has no light, so it gets the white environment and one warning
echo "== (c) the warning, as irad prints it:"
"$irad" render "$scene" "${view[@]}" --size "$size" -o "$tmp/default.png" 2>&1 | grep warning
cp "$tmp/default.png" "$img/env_default_white.png"

# (d) --env-visible on and off: the same lighting, the background shown or black
r "${studio[@]}" --env-visible off -o "$tmp/hidden.png"
python3 scripts/side_by_side.py "$img/env_visible.png" 1 "$tmp/raster.png" "$tmp/hidden.png"

[ "${MEASURE:-0}" = 1 ] || exit 0
# Timing: 256x256, 3 runs of each, the median of each stage from --stats.
median() { sort -g | sed -n 2p; }
time_case() { # NAME ARGS...
  local name=$1; shift
  for i in 1 2 3; do
    "$irad" render "$scene" "${view[@]}" "${studio[@]}" --size 256x256 --quiet "$@" \
      -o "$tmp/t.exr" --stats "$tmp/$name-$i.json"
  done
  python3 - "$name" "$tmp/$name"-[123].json <<'PY'
import json, statistics, sys
runs = [json.load(open(p))["seconds"] for p in sys.argv[2:]]
keys = sorted({k for r in runs for k in r})
print(sys.argv[1],
      " ".join(f"{k} {statistics.median(r.get(k, 0) for r in runs):.3f}" for k in keys))
PY
}
echo "== median seconds of 3 runs at 256x256"
time_case raster-k4
time_case raster-k1 --interleave 1
time_case rt-vpl --estimator rt-vpl
time_case pt-64 --estimator pt --spp 64
time_case pt-256 --estimator pt --spp 256
echo "== error at 128x128 against pt ${REF_SPP:-4096} spp"
s=(--size 128x128 --quiet "${view[@]}" "${studio[@]}")
"$irad" render "$scene" "${s[@]}" --estimator pt --spp "${REF_SPP:-4096}" --seed 7 -o "$tmp/ref.exr"
for c in "raster-k4:" "raster-k1:--interleave 1" "rt-vpl:--estimator rt-vpl" \
         "pt-64:--estimator pt --spp 64" "pt-256:--estimator pt --spp 256"; do
  # shellcheck disable=SC2086
  "$irad" render "$scene" "${s[@]}" ${c#*:} -o "$tmp/e.exr"
  echo "-- ${c%%:*}"
  "$irad" compare "$tmp/e.exr" "$tmp/ref.exr"
done
