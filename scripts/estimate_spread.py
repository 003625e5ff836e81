#!/usr/bin/python3
"""The spread of `skylight estimate` over noise realisations of the same sky (docs/ESTIMATE.md,
"Uncertainty"): for each turbidity and sun, a Preetham fisheye render is perturbed REPS times
(seeds 1..REPS) with multiplicative Gaussian noise (--noise, per pixel and channel) and cloud
occluders (--cloud: that fraction of the image covered by bright discs), each estimated once
(the sample seed = the noise seed); prints the standard deviation of the estimates, their mean
error and the mean reported sigma. Usage:

  scripts/estimate_spread.py [--cli build/skylight] [--reps 20] [--samples N ...] [--noise 0.05]
                             [--cloud 0.1] [--turbidities 2,5,8] [--zeniths 15,45,75]
                             [--estimate-args '--bootstrap 200']

Needs ./build/skylight and Debian's python3-numpy (apt-get install python3-numpy); not run by the
tests (about a minute per sample count over the 12 skies).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3 if kind == b"PF" else 1).copy()


def write_pfm(path, img):
    h, w, _ = img.shape
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(img.astype("<f4").tobytes())


def perturb(img, seed, noise, cloud):
    rng = np.random.default_rng(seed)
    out = img * (1.0 + noise * rng.standard_normal(img.shape))
    h, w, _ = img.shape
    yy, xx = np.mgrid[0:h, 0:w]
    inside = (xx - w / 2 + 0.5) ** 2 + (yy - h / 2 + 0.5) ** 2 <= (min(w, h) / 2) ** 2
    covered = np.zeros((h, w), bool)
    target = cloud * inside.sum()
    bright = np.percentile(img[inside][:, 1], 90)
    while covered[inside].sum() < target:
        cx, cy = rng.uniform(0, w), rng.uniform(0, h)
        r = rng.uniform(0.03, 0.08) * w
        covered |= (xx - cx) ** 2 + (yy - cy) ** 2 <= r * r
    out[covered & inside] = bright * rng.uniform(0.8, 1.6)
    return np.maximum(out, 0.0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default="build/skylight")
    ap.add_argument("--reps", type=int, default=20)
    ap.add_argument("--samples", type=int, nargs="+", default=[100])
    ap.add_argument("--noise", type=float, default=0.05)
    ap.add_argument("--cloud", type=float, default=0.1)
    ap.add_argument("--turbidities", default="2,5,8")
    ap.add_argument("--zeniths", default="15,45,75")
    ap.add_argument("--size", type=int, default=300)
    ap.add_argument("--verbose", action="store_true", help="print every estimate and sigma")
    ap.add_argument("--estimate-args", default="",
                    help="more `skylight estimate` flags, e.g. '--bootstrap 200'")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    print("T    zenith  samples  spread   mean_error  mean_sigma  sigma/spread")
    for t in map(float, a.turbidities.split(",")):
        for z in map(float, a.zeniths.split(",")):
            sky = os.path.join(tmp, "sky.pfm")
            sun = ["--sun-zenith", str(z), "--sun-azimuth", "180"]
            subprocess.run([a.cli, "render", "--model", "preetham", "--turbidity", str(t), *sun,
                            "--projection", "fisheye", "--width", str(a.size), "--height",
                            str(a.size), "-o", sky], check=True, capture_output=True)
            clean = read_pfm(sky)
            photos = []
            for seed in range(1, a.reps + 1):
                p = os.path.join(tmp, f"n{seed}.pfm")
                write_pfm(p, perturb(clean, seed, a.noise, a.cloud))
                photos.append((seed, p))
            for n in a.samples:
                est, sig = [], []
                for seed, p in photos:
                    r = subprocess.run([a.cli, "estimate", "--image", p, "--projection", "fisheye",
                                        *sun, "--samples", str(n), "--seed", str(seed), "--json",
                                        *a.estimate_args.split()],
                                       capture_output=True, text=True)
                    if r.returncode != 0:
                        print(f"  seed {seed}: {r.stderr.strip()}", file=sys.stderr)
                        continue
                    j = json.loads(r.stdout)
                    est.append(j["turbidity"])
                    sig.append(j["turbidity_sigma"])
                    if a.verbose:
                        print(f"  seed {seed}: T {j['turbidity']:.4f} sigma "
                              f"{j['turbidity_sigma']:.4f} inliers {j.get('inliers', '')}")
                est, sig = np.array(est), np.array(sig)
                spread = est.std(ddof=1)
                print(f"{t:<4g} {z:<7g} {n:<8d} {spread:<8.3f} {abs(est.mean() - t):<11.3f} "
                      f"{sig.mean():<11.3f} {sig.mean() / spread if spread > 0 else float('nan'):.2f}",
                      flush=True)


if __name__ == "__main__":
    main()
