#!/usr/bin/env bash
# The renders of docs/ATMOSPHERE.md ("Renders"): nishita (single scattering), hillaire and
# bruneton (multiple scattering) in four scenes, as tone-mapped PNG previews (one exposure per
# image) into OUT_DIR (default ./atmosphere_images; copy them to docs/images/atmosphere/ to
# regenerate the docs' images). bruneton's tables are kept in OUT_DIR/tables between the renders
# (SKYLIGHT_TABLE_CACHE), so each planet's are computed once.
# Usage: scripts/render_atmosphere_images.sh [OUT_DIR] [path/to/skylight]
set -euo pipefail
out="${1:-atmosphere_images}"
sk="${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build/skylight}"
mkdir -p "$out"
export SKYLIGHT_TABLE_CACHE="$out/tables"
up=(--projection fisheye --width 180 --height 180)
# scene | flags
scenes=(
  "day|--sun-elevation 30 --sun-azimuth 225 ${up[*]}"
  "sunset|--sun-elevation 2 --sun-azimuth 270 ${up[*]}"
  "twilight|--sun-elevation -4 --sun-azimuth 270 ${up[*]}"
  "orbit|--observer-altitude 400000 --albedo 0.3 --sun-elevation 20 --sun-azimuth 180 --projection camera --look-elevation -15 --look-azimuth 180 --fov 90 --width 288 --height 180"
)
for model in nishita hillaire bruneton; do
  for entry in "${scenes[@]}"; do
    scene="${entry%%|*}"
    read -r -a flags <<<"${entry#*|}"
    "$sk" render --model "$model" "${flags[@]}" -o "$out/${model}_$scene.exr" \
      --preview "$out/${model}_$scene.png"
    rm "$out/${model}_$scene.exr"
  done
done
rm -rf "$SKYLIGHT_TABLE_CACHE"
echo "wrote $(ls "$out"/*.png | wc -l) images to $out"
