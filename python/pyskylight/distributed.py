"""pyskylight.distributed: skylight's work beyond one machine, on Dask (docs/SCALE.md).

Each function takes a ``dask.distributed.Client`` (default: the current one, ``get_client()``),
submits one task per input (every task is one call into the library, which releases the GIL
while it works) and returns a summary: one dict per input, in the inputs' order, with its
``status`` ("ok", "skipped": the output was already complete, "failed": the input's error) and,
when failed, the library's one-line ``error``. A failed input never stops the others; each is
logged as one line on the ``pyskylight.distributed`` logger.

Nothing is lost: the library writes every output to a temporary name beside it and renames it
when complete (io/file.h), so an output is either whole or absent; a worker killed mid-task loses
only its temporary, and Dask runs the task again on another worker (its ``allowed-failures``);
``overwrite=False`` skips inputs whose output exists. ``progress=True`` shows Dask's progress bar
(in a terminal or a notebook).
"""

import ctypes
import ctypes.util
import logging
import os
import time

import pyskylight as _sk

_log = logging.getLogger("pyskylight.distributed")

__all__ = ["sky_matrices", "estimate_turbidity", "measured_compare", "train_networks",
           "tune_allocator"]


# glibc's mallopt parameters and the values the workers take (docs/SCALE.md, "Memory"): Dask's
# nanny starts workers with MALLOC_TRIM_THRESHOLD_=65536, which also freezes glibc's mmap threshold
# at 128 KiB, so every multi-megabyte buffer of a task (a year's matrix, its .npy) is mmapped and
# zero-filled anew: +50 % per task, measured. Above these sizes memory still goes back to the OS.
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_TRIM_BYTES, _MMAP_BYTES = 128 << 20, 64 << 20
_tuned = False
# What the library raises for an input it cannot use: bad values or files (InvalidArgument, a
# ValueError), I/O (OSError), a fit outside its bound (RuntimeError, nothing written).
_LIBRARY_ERRORS = (_sk.InvalidArgument, OSError, RuntimeError)


def tune_allocator():
    """Raises glibc's mmap and trim thresholds in this process (once; a no-op elsewhere). Every
    task of this module calls it in its worker; scripts/scale_bench.py calls it in the serial
    baseline too, so that both run the same allocator."""
    global _tuned
    if _tuned:
        return
    _tuned = True
    name = ctypes.util.find_library("c")
    if not name:
        return
    try:
        libc = ctypes.CDLL(name)
        libc.mallopt(_M_MMAP_THRESHOLD, _MMAP_BYTES)
        libc.mallopt(_M_TRIM_THRESHOLD, _TRIM_BYTES)
    except (OSError, AttributeError):  # not glibc
        pass


def _client(client):
    if client is not None:
        return client
    from distributed import get_client
    return get_client()


def _gather(client, function, items, progress, **constants):
    """One task per item (not cached by Dask: pure=False), their results in the items' order."""
    futures = client.map(function, items, pure=False, **constants)
    if progress:
        from distributed import progress as _progress
        _progress(futures)
    results = client.gather(futures)
    for r in results:
        if r["status"] == "failed":
            _log.warning("%s failed: %s", r["input"], r["error"])
    return results


def _sky_matrix_task(item, options, overwrite, before_task=None):
    """One weather file's matrix: ``skylight daylight --epw IN -o OUT`` in the worker."""
    tune_allocator()
    epw, output = item
    result = {"input": epw, "site": os.path.splitext(os.path.basename(epw))[0], "output": output,
              "hours": None, "seconds": 0.0, "status": "ok", "error": None}
    if not overwrite and os.path.exists(output):
        result["status"] = "skipped"
        return result
    if before_task is not None:
        before_task(item)
    start = time.perf_counter()
    try:
        record = _sk.run("daylight", epw=epw, output=output, **options)
    except _LIBRARY_ERRORS as e:
        result.update(status="failed", error=str(e), output=None)
        return result
    result["hours"] = record["hours"]
    result["seconds"] = time.perf_counter() - start
    return result


def sky_matrices(epw_paths, out_dir, patches="tregenza", quantity="radiance", sun_patches=4,
                 client=None, overwrite=False, progress=False, before_task=None, **options):
    """The annual sky matrix of each weather file (``skylight daylight --epw``, docs/DAYLIGHT.md)
    as ``out_dir/<name>.npy``: one task per file. ``options``: daylight's other matrix parameters
    (``hours``, ``ground_albedo``, ``compat``, ``channels``). ``before_task(item)``, when given, is
    called in the worker with each (weather file, output) before its work, e.g. to stage the file
    on the worker's disk (it must be picklable). Returns one dict per file: ``site``,
    ``input``, ``output``, ``hours`` (the matrix's rows), ``seconds`` (the task's wall time),
    ``status``, ``error``. Two files with the same name are refused before any work."""
    epw_paths = [os.fspath(p) for p in epw_paths]
    names = [os.path.splitext(os.path.basename(p))[0] for p in epw_paths]
    seen = {}
    for path, name in zip(epw_paths, names):
        if name in seen:
            raise _sk.InvalidArgument(
                f"sky_matrices: '{seen[name]}' and '{path}' would both write {name}.npy")
        seen[name] = path
    os.makedirs(out_dir, exist_ok=True)
    items = [(p, os.path.join(os.fspath(out_dir), n + ".npy")) for p, n in zip(epw_paths, names)]
    constants = dict(options, patches=patches, quantity=quantity, sun_patches=sun_patches)
    return _gather(_client(client), _sky_matrix_task, items, progress, options=constants,
                   overwrite=overwrite, before_task=before_task)


def _estimate_task(image, options):
    tune_allocator()
    result = {"input": image, "photo": image, "model": None, "turbidity": None,
              "turbidity_sigma": None, "sun_zenith_deg": None, "sun_azimuth_deg": None,
              "sun_source": None, "seconds": 0.0, "status": "ok", "error": None}
    start = time.perf_counter()
    try:
        record = _sk.run("estimate", image=image, **options)
    except _LIBRARY_ERRORS as e:
        result.update(status="failed", error=str(e))
        return result
    for key in ("model", "turbidity", "turbidity_sigma", "sun_zenith_deg", "sun_azimuth_deg",
                "sun_source"):
        result[key] = record[key]
    result["seconds"] = time.perf_counter() - start
    return result


def estimate_turbidity(image_paths, client=None, progress=False, **options):
    """Turbidity (or the model's parameter) of each sky photo (``skylight estimate``,
    docs/ESTIMATE.md): one task per photo, ``options`` the estimate's (``projection``, ``lens``,
    ``camera``, the sun, ``model``, ...). Returns one dict per photo: ``photo``, ``model``,
    ``turbidity``, ``turbidity_sigma``, ``sun_zenith_deg``, ``sun_azimuth_deg``, ``sun_source``,
    ``seconds``, ``status``, ``error``. Nothing is written."""
    images = [os.fspath(p) for p in image_paths]
    return _gather(_client(client), _estimate_task, images, progress, options=options)


def _measured_task(item, options):
    tune_allocator()
    folder, model = item
    result = {"input": folder if folder is not None else "(the shipped subset)", "kider": folder,
              "model": model, "captures": None, "median_luminance_rms_shape": None,
              "median_luminance_rms_abs": None, "median_scale": None, "seconds": 0.0,
              "status": "ok", "error": None, "record": None}
    start = time.perf_counter()
    args = dict(options, model=model)
    if folder is not None:
        args["kider"] = folder
    try:
        record = _sk.run("measured", **args)
    except _LIBRARY_ERRORS as e:
        result.update(status="failed", error=str(e))
        return result
    result.update(captures=len(record["captures"]), record=record,
                  median_luminance_rms_shape=record["median_luminance_rms_shape"],
                  median_luminance_rms_abs=record["median_luminance_rms_abs"],
                  median_scale=record["median_scale"], seconds=time.perf_counter() - start)
    return result


def measured_compare(capture_dirs, models=("preetham", "hosek", "cie"), client=None,
                     progress=False, **options):
    """Every model fitted to every capture of each folder of Kider et al. 2014's captures
    (``skylight measured``, docs/MEASURED.md): one task per (folder, model); a folder None is the
    shipped subset. ``options``: measured's (``exclude_sun_deg``, ``sun_azimuth_from``, the site).
    Returns one dict per (folder, model), folders outer: ``kider``, ``model``, ``captures``, the
    medians ``median_luminance_rms_shape``, ``median_luminance_rms_abs``, ``median_scale``, the
    whole ``record`` (every capture's fit), ``seconds``, ``status``, ``error``."""
    items = [(None if d is None else os.fspath(d), m) for d in capture_dirs for m in models]
    return _gather(_client(client), _measured_task, items, progress, options=options)


def _train_task(item, overwrite):
    tune_allocator()
    name, output, config = item
    result = {"input": name, "name": name, "output": output, "seconds": 0.0, "status": "ok",
              "error": None, "record": None}
    if not overwrite and os.path.exists(output):
        result["status"] = "skipped"
        return result
    start = time.perf_counter()
    try:
        result["record"] = _sk.run("nn train", output=output, **config)
    except _LIBRARY_ERRORS as e:
        result.update(status="failed", error=str(e), output=None)
        return result
    result["seconds"] = time.perf_counter() - start
    return result


def train_networks(configs, out_dir, client=None, overwrite=False, progress=False):
    """One trained network per configuration (``skylight nn train``, docs/NN.md): ``configs`` maps
    a name to nn train's parameters (``source``, ``seed``, ``iterations``, ``starts``, ...); each
    network is written to ``out_dir/<name>.json``. A network that fails its held-out check is a
    failed task (the library writes nothing). Returns one dict per configuration, in order:
    ``name``, ``output``, ``record`` (nn train's: the held-out errors), ``seconds``, ``status``,
    ``error``."""
    os.makedirs(out_dir, exist_ok=True)
    items = [(name, os.path.join(os.fspath(out_dir), name + ".json"), dict(config))
             for name, config in configs.items()]
    return _gather(_client(client), _train_task, items, progress, overwrite=overwrite)
