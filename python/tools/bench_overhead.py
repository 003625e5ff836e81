#!/usr/bin/python3
"""The Python binding's overhead (issue 30): Sky.evaluate_directions(..., quantity="xyz",
threads=1) on 2^20 directions, into a new array and into out=, against the C++ batch path in the same process (the extension's
batch_cpu_seconds: tristimulus_batch over the same directions in structure-of-arrays floats,
one thread, CPU time). Prints the median of `--repeat` runs of each, in CPU time of the process
(time.process_time: one thread, so equal to the thread's).

Usage: PYTHONPATH=build/python /usr/bin/python3 python/tools/bench_overhead.py [--repeat 7]
"""

import argparse
import statistics
import time

import numpy as np

import skylight

MODELS = [("preetham", {"turbidity": 3}), ("hosek", {"turbidity": 3, "albedo": 0.3}),
          ("nn", {"turbidity": 3})]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--n", type=int, default=1 << 20)
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    v = rng.normal(size=(args.n, 3))
    v[:, 2] = np.abs(v[:, 2])
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    soa = [np.ascontiguousarray(v[:, k], dtype=np.float32) for k in range(3)]
    print(f"{'model':10} {'python ms':>10} {'with out= ms':>13} {'C++ batch ms':>13} "
          f"{'ratio':>6} {'ratio out=':>10}")
    for name, kw in MODELS:
        sky = skylight.Sky(name, sun_zenith=45, sun_azimuth=180, **kw)
        py, py_out, cpp = [], [], []
        out = np.empty((args.n, 3))
        for _ in range(args.repeat):
            t0 = time.process_time()
            sky.evaluate_directions(v, quantity="xyz", threads=1)
            py.append(time.process_time() - t0)
            t0 = time.process_time()
            sky.evaluate_directions(v, quantity="xyz", threads=1, out=out)
            py_out.append(time.process_time() - t0)
            cpp.append(sky._sky.batch_cpu_seconds(*soa))
        p, po, c = statistics.median(py), statistics.median(py_out), statistics.median(cpp)
        print(f"{name:10} {1e3 * p:10.2f} {1e3 * po:13.2f} {1e3 * c:13.2f} {p / c:6.2f} "
              f"{po / c:10.2f}")
    # The cost of a call itself: 16 directions.
    sky = skylight.Sky("preetham", sun_zenith=45, sun_azimuth=180, turbidity=3)
    few = v[:16]
    calls = []
    for _ in range(args.repeat):
        t0 = time.process_time()
        for _ in range(1000):
            sky.evaluate_directions(few, quantity="xyz", threads=1)
        calls.append((time.process_time() - t0) / 1000)
    print(f"one call on 16 directions: {1e6 * statistics.median(calls):.1f} us")


if __name__ == "__main__":
    main()
