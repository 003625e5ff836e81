"""Measured clear skies (Kider et al. 2014; docs/MEASURED.md): the captures as arrays, and a sky
model fitted to each of them with its errors (the ``measured`` operation)."""

import os as _os


def load_kider(path=None):
    """The captures under ``path`` (a folder of Kider et al. 2014's data set, a date, its RADIANCE
    folder, one capture, or the shipped subset's folder; None: the shipped subset embedded in the
    library), sorted by name. Each is a dict: ``name``, ``local_time`` (ISO 8601, EDT),
    ``wavelengths_nm`` (W), per sample in index order (81) ``index``, ``zenith_deg``,
    ``azimuth_deg`` (from north towards east), ``luminance`` [cd/m^2], ``radiance`` (81 x W,
    W m^-2 sr^-1 nm^-1) and ``replaced`` (sample 0: its ring neighbours' mean), and the
    pyranometer's ``pyranometer_w_m2``, ``pyranometer_time`` and their mean
    ``global_horizontal_w_m2`` (None without a pyranometer file)."""
    from . import _skylight
    return _skylight.read_kider(None if path is None else _os.fspath(path))


def compare(model, kider=None, progress=None, **options):
    """``model`` fitted to each capture (the ``measured`` operation): its record, with one entry
    per capture (``parameters``, ``scale``, ``luminance_rms_shape``, ``luminance_rms_abs``,
    ``spectral_rms``, ``mean_delta_uv``, the global horizontal irradiance and ``samples``).
    ``kider``: a folder as ``load_kider`` takes (None: the shipped subset); ``options``: the
    operation's (``exclude_sun_deg``, ``sun_azimuth_from``, ``output`` for the CSV, ...)."""
    from . import run
    if kider is not None:
        options["kider"] = _os.fspath(kider)
    return run("measured", progress=progress, model=model, **options)
