#!/usr/bin/env bash
# Regenerates the images and numbers of docs/ext/specular.md (about 35 minutes on 2 cores, the
# two 4096-spp path-traced references being most of it). SPP and SIZE override the defaults
# (4096, 256x256) for a quick trial run.
# Usage: scripts/specular_docs.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
irad="${1:-build}/bin/irad"
spp="${SPP:-4096}"
size="${SIZE:-256x256}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
img=docs/images
export LP_NUM_THREADS=2
for scene in wall panel; do
  file=data/cornell_mirror.gltf
  if [ "$scene" = panel ]; then file=data/cornell_mirror_panel.gltf; fi
  out="$img/ext_specular_${scene}"
  "$irad" render "$file" --estimator pt --spp "$spp" --size "$size" -o "$tmp/$scene-pt.exr" --quiet
  "$irad" render "$file" --paths 1024 --size "$size" -o "$tmp/$scene-raster.exr" \
    --stats "$tmp/$scene-raster.json"
  "$irad" render "$file" --estimator rt-vpl --paths 1024 --size "$size" \
    -o "$tmp/$scene-rtvpl.exr" --stats "$tmp/$scene-rtvpl.json"
  for e in pt raster rtvpl; do
    "$irad" convert "$tmp/$scene-$e.exr" -o "$tmp/$scene-$e.png" --exposure 1
  done
  for e in raster rtvpl; do
    echo "== $scene: $e against pt (pixels, then 8x8 blocks)"
    "$irad" compare "$tmp/$scene-$e.exr" "$tmp/$scene-pt.exr" --diff "$tmp/$scene-$e-error.png"
    "$irad" compare "$tmp/$scene-$e.exr" "$tmp/$scene-pt.exr" --block 8
  done
  python3 scripts/side_by_side.py "${out}_raster_pt.png" 1 "$tmp/$scene-raster.png" \
    "$tmp/$scene-pt.png"
  python3 scripts/side_by_side.py "${out}_rtvpl_pt.png" 1 "$tmp/$scene-rtvpl.png" \
    "$tmp/$scene-pt.png"
  python3 scripts/side_by_side.py "${out}_error.png" 1 "$tmp/$scene-raster-error.png" \
    "$tmp/$scene-rtvpl-error.png"
done
# What the panel changes: the panel scene against the box without it (0 to 30 %).
"$irad" render data/cornell_box.gltf --paths 1024 --size "$size" -o "$tmp/box-raster.exr" --quiet
"$irad" compare "$tmp/panel-raster.exr" "$tmp/box-raster.exr" --diff-max 0.3 \
  --diff "$img/ext_specular_panel_vs_box.png" >/dev/null
