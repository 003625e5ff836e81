#!/usr/bin/python3
"""The measurements of docs/SCALE.md: N weather years -> annual Tregenza matrices (.npy), one by
one in this process (the library's serial time), then through pyskylight.distributed on a
LocalCluster of 1 and of 2 worker processes (one thread each); and M sky photos' turbidity, one
by one and on 2 workers. Prints one JSON record: wall times, the speed-up 1 -> 2 workers, Dask's
overhead over the serial library time, the workers' peak memory, the outputs' bit-equality.

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/scale_bench.py [N] [M]  (default 40, 20)
The years are copies of data/weather/synthetic_munich.epw under N names (the matrix's cost does
not depend on the file's numbers); the photos are copies of data/hdr_sky/city.exr.
"""
import filecmp
import json
import os
import shutil
import sys
import tempfile
import time

import distributed

import pyskylight as sk
from pyskylight import distributed as skd

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def cluster_run(workers, function, *args, **kwargs):
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        # The workers are up and have imported pyskylight (numpy, the extension: ~0.2 s once per
        # worker process) before the clock starts.
        client.run(skd.tune_allocator)
        start = time.perf_counter()
        result = function(*args, client=client, **kwargs)
        wall = time.perf_counter() - start
        memory = max(w["metrics"]["memory"] for w in client.scheduler_info()["workers"].values())
    return result, wall, memory


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    m = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    epw = os.path.join(ROOT, "data", "weather", "synthetic_munich.epw")
    photo = os.path.join(ROOT, "data", "hdr_sky", "city.exr")
    with tempfile.TemporaryDirectory(prefix="skylight-scale-") as tmp:
        years = []
        for k in range(n):
            years.append(os.path.join(tmp, f"site{k:03d}.epw"))
            shutil.copyfile(epw, years[-1])
        skd.tune_allocator()  # the workers' allocator settings (docs/SCALE.md, "Memory")
        serial_dir = os.path.join(tmp, "serial")
        os.makedirs(serial_dir)
        start = time.perf_counter()
        for y in years:
            sk.run("daylight", epw=y, output=os.path.join(serial_dir, os.path.basename(y)[:-4] + ".npy"),
                   patches="tregenza")
        serial = time.perf_counter() - start
        runs = {}
        for workers in (1, 2):
            out = os.path.join(tmp, f"dask{workers}")
            summary, wall, memory = cluster_run(workers, skd.sky_matrices, years, out)
            equal = all(r["status"] == "ok" and filecmp.cmp(
                r["output"], os.path.join(serial_dir, r["site"] + ".npy"), shallow=False)
                for r in summary)
            runs[workers] = {"wall_s": wall, "worker_memory_peak_mb": memory / 2**20,
                             "bit_equal_to_serial": equal,
                             "task_seconds_median": sorted(r["seconds"] for r in summary)[n // 2]}
        photos = []
        for k in range(m):
            photos.append(os.path.join(tmp, f"photo{k:03d}.exr"))
            shutil.copyfile(photo, photos[-1])
        start = time.perf_counter()
        one = [sk.run("estimate", image=p, projection="equirect")["turbidity"] for p in photos]
        photo_serial = time.perf_counter() - start
        rows, photo_wall, _ = cluster_run(2, skd.estimate_turbidity, photos, projection="equirect")
    record = {
        "sites": n, "serial_library_s": serial, "per_site_year_s": serial / n,
        "dask": runs,
        "speedup_2_vs_1_workers": runs[1]["wall_s"] / runs[2]["wall_s"],
        "dask_overhead_1_worker": runs[1]["wall_s"] / serial - 1.0,
        "photos": m, "photo_serial_s": photo_serial, "per_photo_s": photo_serial / m,
        "photo_2_workers_s": photo_wall,
        "photo_same_turbidity": [r["turbidity"] for r in rows] == one,
    }
    print(json.dumps(record, indent=2))


if __name__ == "__main__":
    main()
