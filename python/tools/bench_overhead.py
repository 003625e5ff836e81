#!/usr/bin/python3
"""The Python binding's overhead (docs/PYTHON.md): 2^20 directions, one thread, CPU time
(time.thread_time of the calling thread, which does all the work with threads=1), medians of `--repeat` runs, against
the C++ batch paths in the same process (the extension's *_cpu_seconds, timed around the library
call alone, writing into the same output arrays as the Python calls):

  evaluate_directions(v, quantity="xyz") on float64 rows (N, 3), into a new array and into out=,
      against sl::evaluate_rows on the same rows (the C++ path for that layout);
  evaluate_soa(x, y, z) on float32 arrays (N,), into out=, against sl::evaluate_soa on the same
      arrays (C++ checked) and against tristimulus_batch alone (the models' SIMD kernel: no
      checks of the directions and results, no conversion).

The last column, rows / kernel, is the cost of the float64 layout itself (C++ alone).

Usage: PYTHONPATH=build/python /usr/bin/python3 python/tools/bench_overhead.py [--repeat 7]
"""

import argparse
import statistics
import time

import numpy as np

import pyskylight

MODELS = [("preetham", {"turbidity": 3}), ("hosek", {"turbidity": 3, "albedo": 0.3}),
          ("nn", {"turbidity": 3})]


# Written before each timed call, so that every call starts with the same (cold) cache: the
# order of the calls would otherwise favour the one that runs just after another wrote its output.
_SCRATCH = np.zeros(64 << 20, dtype=np.uint8)


def cpu(fn):
    _SCRATCH.fill(1)
    t0 = time.thread_time()
    fn()
    return time.thread_time() - t0


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
    print(f"{'model':9} {'rows py':>8} {'out=':>7} {'C++':>7} {'ratio':>6} {'ratio out=':>10} | "
          f"{'soa py':>7} {'C++':>7} {'kernel':>7} {'ratio':>6} {'/kernel':>7} | "
          f"{'rows/kernel':>11}   (ms)")
    for name, kw in MODELS:
        sky = pyskylight.Sky(name, sun_zenith=45, sun_azimuth=180, **kw)
        out = np.empty((args.n, 3))
        out32 = np.empty((3, args.n), dtype=np.float32)
        t = {k: [] for k in ("py", "py_out", "rows", "soa", "checked", "kernel")}
        for _ in range(args.repeat):
            t["py"].append(cpu(lambda: sky.evaluate_directions(v, quantity="xyz", threads=1)))
            t["py_out"].append(
                cpu(lambda: sky.evaluate_directions(v, quantity="xyz", threads=1, out=out)))
            _SCRATCH.fill(4)
            t["rows"].append(sky._sky.rows_cpu_seconds(v, out))
            t["soa"].append(cpu(lambda: sky.evaluate_soa(*soa, threads=1, out=out32)))
            _SCRATCH.fill(2)
            t["checked"].append(sky._sky.batch_cpu_seconds(*soa, out32, True))
            _SCRATCH.fill(3)
            t["kernel"].append(sky._sky.batch_cpu_seconds(*soa, out32, False))
        m = {k: 1e3 * statistics.median(x) for k, x in t.items()}
        print(f"{name:9} {m['py']:8.2f} {m['py_out']:7.2f} {m['rows']:7.2f} "
              f"{m['py'] / m['rows']:6.3f} {m['py_out'] / m['rows']:10.3f} | {m['soa']:7.2f} "
              f"{m['checked']:7.2f} {m['kernel']:7.2f} {m['soa'] / m['checked']:6.3f} "
              f"{m['soa'] / m['kernel']:7.3f} | {m['rows'] / m['kernel']:11.2f}")
    # The cost of a call itself: 16 directions.
    sky = pyskylight.Sky("preetham", sun_zenith=45, sun_azimuth=180, turbidity=3)
    few = v[:16]
    calls = []
    for _ in range(args.repeat):
        calls.append(cpu(lambda: [sky.evaluate_directions(few, quantity="xyz", threads=1)
                                  for _ in range(1000)]) / 1000)
    print(f"one call on 16 directions: {1e6 * statistics.median(calls):.1f} us")


if __name__ == "__main__":
    main()
