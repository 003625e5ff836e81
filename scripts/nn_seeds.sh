#!/usr/bin/env bash
# Trains the paper protocol's network for seeds 1-10 and prints, per seed, the validation errors,
# the held-out check, the CPU time and the iterations (docs/NN.md, "Every seed"):
#   scripts/nn_seeds.sh SOURCE [nn train flags...]      e.g. scripts/nn_seeds.sh preetham --starts 1
# Needs ./build/skylight (scripts/build.sh build). Minutes: 20-60 s of CPU time per seed.
set -euo pipefail
src="$1"
shift
cli="${SKYLIGHT_CLI:-./build/skylight}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for seed in 1 2 3 4 5 6 7 8 9 10; do
  # --max-error 1000: report every seed, also one the default bound would refuse.
  log="$(/usr/bin/time -f "cpu %U s" "$cli" nn train --source "$src" --seed "$seed" \
    --max-error 1000 "$@" -o "$out/s$seed.json" 2>&1)"
  validation="$(grep '^validation' <<<"$log" | sed 's/^validation: //')"
  held_out="$(grep '^held-out' <<<"$log" | sed -E 's/^held-out check: relative error //; s/ \(bound.*//')"
  cpu="$(grep '^cpu' <<<"$log")"
  its="$(grep '^nn train:' <<<"$log" | sed -E 's/.*seed [0-9]+: //; s/, training.*//')"
  echo "$src seed $seed | $validation | held-out $held_out | $cpu | $its"
done
