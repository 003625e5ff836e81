#!/usr/bin/env bash
# Morales et al. 2017 Table 1 protocol with the CLI (docs/ESTIMATE.md): 500 x 500 equidistant
# fisheye Preetham skies, theta_s = 58.4 deg, phi_s = -179.4 deg, T = 2..9; N = 100 random sample
# points per estimate, REPS estimates (seeds 1..REPS) per image; prints T, mean, sigma, |mean - T|.
# Usage: scripts/estimate_table1.sh BUILD_DIR [REPS] [extra estimate flags, e.g. --no-ransac]
set -euo pipefail
build="$1"; reps="${2:-100}"; shift; shift || true
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
sun=(--sun-zenith 58.4 --sun-azimuth -179.4)
printf '%-4s %-12s %-10s %-10s\n' T mean sigma error
for t in 2 3 4 5 6 7 8 9; do
  "$build/skylight" render --model preetham --turbidity "$t" "${sun[@]}" --projection fisheye \
    --width 500 --height 500 -o "$tmp/sky$t.exr" 2> "$tmp/render.log" ||
    { cat "$tmp/render.log" >&2; exit 1; }  # (T > 6 warns: outside Preetham's fitted range)
  for seed in $(seq 1 "$reps"); do
    "$build/skylight" estimate --image "$tmp/sky$t.exr" "${sun[@]}" --samples 100 --seed "$seed" \
      --json "$@" | sed -n 's/^  "turbidity": \(.*\),$/\1/p'
  done | awk -v t="$t" '{ s += $1; q += $1 * $1; n++ }
    END { m = s / n; v = (q - n * m * m) / (n - 1); if (v < 0) v = 0;
          d = m - t; if (d < 0) d = -d; printf "%-4s %-12.8f %-10.2e %-10.2e\n", t, m, sqrt(v), d }'
done
