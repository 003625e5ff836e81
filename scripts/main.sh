#!/usr/bin/env bash
# The main job (README): installs what is missing, builds the CLI and the Python package
# (scripts/build_main.sh), and renders the default sky of every
# model into out/ — float EXR (with metadata), a tone-mapped PNG preview, and a log-luminance
# false-colour map with legend — as a full-sphere equirect map and an upward fisheye (the Perez
# sky also from measured irradiance); the annual Tregenza sky matrix of the sample weather year
# (docs/DAYLIGHT.md) and its hourly light on a south façade (docs/IRRADIANCE.md); then the
# validation and comparison report to out/report/ (docs/REPORT.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/setup.sh
bash scripts/build_main.sh
out="${SKYLIGHT_OUT:-$root/out}"
mkdir -p "$out"
sk="$root/build/skylight"
sun=(--sun-zenith 45 --sun-azimuth 180)
# bruneton's precomputed tables, computed once for the renders and the report (io/table_cache.h).
export SKYLIGHT_TABLE_CACHE="${SKYLIGHT_TABLE_CACHE:-$out/tables}"
# name | model flags
skies=(
  "preetham_T3|--model preetham --turbidity 3"
  "preetham_T6|--model preetham --turbidity 6"
  "cie_type12|--model cie --cie-type 12"
  "cie_type7|--model cie --cie-type 7"
  "cie_type16|--model cie --cie-type 16"
  "hosek_T3|--model hosek --turbidity 3 --albedo 0.3"
  "nishita_earth|--model nishita"
  "hillaire_earth|--model hillaire"
  "bruneton_earth|--model bruneton"
  "perez_clear|--model perez --perez -1,-0.32,10,-3,0.45 --zenith-luminance 5000"
  "perez_measured|--model perez --dni 600 --dhi 120 --day-of-year 172"
)
n=${#skies[@]}; i=0
for entry in "${skies[@]}"; do
  i=$((i + 1))
  name="${entry%%|*}"; read -r -a flags <<<"${entry#*|}"
  echo "[$i/$n] $name"
  "$sk" render "${flags[@]}" "${sun[@]}" --projection equirect --width 1024 --height 512 \
    -o "$out/$name.exr" --preview "$out/$name.png" --false-colour "$out/${name}_false_colour.png"
  "$sk" render "${flags[@]}" "${sun[@]}" --projection fisheye --width 512 --height 512 \
    -o "$out/${name}_fisheye.exr" --false-colour "$out/${name}_fisheye_false_colour.png"
done
echo "[daylight] $out/sky_matrix_tregenza.csv"
"$sk" daylight --epw data/weather/synthetic_munich.epw --patches tregenza -o "$out/sky_matrix_tregenza.csv"
echo "[irradiance] $out/facade_south.csv"
"$sk" irradiance --model perez --epw data/weather/synthetic_munich.epw --tilt 90 --surface-azimuth 180 \
  -o "$out/facade_south.csv"
echo "[report] $out/report"
"$sk" report -o "$out/report"
echo "wrote $(ls "$out" | wc -l) entries to $out; the report: $out/report/index.html"
