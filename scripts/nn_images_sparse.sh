#!/usr/bin/env bash
# Trains a sky network on a sparse sequence of rendered captures and measures it between them
# (docs/NN.md, "Sparse sequences"): 7 captures of Hosek-Wilkie T 3 with the solar disc, suns 10 deg
# apart (zenith 15-75 deg, azimuth 120-210 deg), the suns found in the images; then the network
# against the model at the 6 suns half-way between the captures, over the sky (view zenith < 88 deg,
# more than 5 deg from the sun):
#   scripts/nn_images_sparse.sh [nn train flags...]       e.g. scripts/nn_images_sparse.sh --seed 2
# Needs ./build/skylight (scripts/build.sh build) and /usr/bin/python3. Minutes.
set -euo pipefail
cli="${SKYLIGHT_CLI:-./build/skylight}"
model="${MODEL:-hosek}" z0="${Z0:-15}" a0="${A0:-120}" da="${DA:-15}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "file" >"$out/seq.csv"
for k in 0 1 2 3 4 5 6; do
  "$cli" render --model "$model" --turbidity 3 --include-sun --sun-zenith $((z0 + 10 * k)) \
    --sun-azimuth $((a0 + da * k)) --width 128 --height 64 -o "$out/c$k.exr" >/dev/null
  echo "c$k.exr" >>"$out/seq.csv"
done
set +e
/usr/bin/time -f "cpu %U s" "$cli" nn train --images "$out/seq.csv" "$@" -o "$out/w.json" 2>&1 |
  grep -vE '^\s+[0-9]+ +c[0-9].exr' | tail -n 8
status=${PIPESTATUS[0]}
set -e
[[ $status -eq 0 ]] || { echo "nn train exit $status"; exit 0; }
/usr/bin/python3 - "$cli" "$out" "$model" "$z0" "$a0" "$da" <<'PY'
import math, subprocess, sys
cli, out, model = sys.argv[1], sys.argv[2], sys.argv[3]
z0, a0, da = (float(x) for x in sys.argv[4:7])
errors_all = []
for k in range(6):
    sz, sa = z0 + 5 + 10 * k, a0 + da * (k + 0.5)
    s = (math.sin(math.radians(sz)) * math.sin(math.radians(sa)),
         math.sin(math.radians(sz)) * math.cos(math.radians(sa)), math.cos(math.radians(sz)))
    dirs = []
    for i in range(44):
        z = 1 + 2 * i
        for j in range(90):
            a = 2 + 4 * j
            v = (math.sin(math.radians(z)) * math.sin(math.radians(a)),
                 math.sin(math.radians(z)) * math.cos(math.radians(a)), math.cos(math.radians(z)))
            if math.degrees(math.acos(max(-1, min(1, sum(p * q for p, q in zip(s, v)))))) > 5:
                dirs.append(f"{z},{a}")
    text = "zenith_deg,azimuth_deg\n" + "\n".join(dirs) + "\n"
    def ev(args):
        r = subprocess.run([cli, "eval", "--sun-zenith", str(sz), "--sun-azimuth", str(sa)] + args,
                           input=text, capture_output=True, text=True, check=True)
        rows = [l.split(",") for l in r.stdout.splitlines() if l and l[0].isdigit()]
        return [sum(float(x) for x in row[-3:]) for row in rows]
    net = ev(["--model", "nn", "--weights", f"{out}/w.json"])
    ref = ev(["--model", model, "--turbidity", "3"])
    e = sorted(abs(n / r - 1) for n, r in zip(net, ref))
    errors_all += e
    print(f"between captures, sun {sz:g} deg, {sa:g} deg: median {100 * e[len(e) // 2]:.2f} %, "
          f"p95 {100 * e[int(0.95 * len(e))]:.2f} %, max {100 * e[-1]:.1f} %")
e = sorted(errors_all)
print(f"all 6 suns: median {100 * e[len(e) // 2]:.2f} %, p95 {100 * e[int(0.95 * len(e))]:.2f} %")
PY
