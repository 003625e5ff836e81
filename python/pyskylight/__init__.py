"""pyskylight: the Python package of skylight (daylight sky models, the physical atmosphere and the
sky tools of the C++ library). Its import name is ``pyskylight`` (another, unrelated package on PyPI
is called ``skylight``; docs/PYTHON.md).

Every parameter comes from the library's schemas: names, units, ranges and defaults are those of
``skylight models --json`` (``pyskylight.models()``), with ``-`` spelled ``_``. Every operation of
the library runs through :func:`run` (``skylight operations --json``, ``pyskylight.operations()``),
with the command line's checks and messages. A bad value raises ``pyskylight.InvalidArgument`` (a
``ValueError``) with the library's message naming the parameter; I/O errors raise ``OSError``; what
the command line prints as a warning is a ``pyskylight.SkylightWarning``. docs/PYTHON.md in the
repository has the guide.
"""

import datetime as _dt
import json as _json
import keyword as _keyword
import os as _os
import tempfile as _tempfile

import numpy as _np

try:
    from ._skylight import InvalidArgument, SkylightWarning, __version__
    from . import _skylight
except ImportError as _e:  # the message is the point: what to build
    raise ImportError(
        "pyskylight's extension module pyskylight._skylight is not built here "
        f"({_os.path.dirname(__file__)}): build it with `cmake --build build --target "
        "skylight_python` (the README's main job, ./scripts/main.sh, builds it; docs/PYTHON.md), "
        f"or install the package with `pip install --no-build-isolation .` ({_e})") from None
from . import estimate
from . import haze
from . import io
from . import measured
from . import nn
from . import sh

__all__ = ["InvalidArgument", "SkylightWarning", "Sky", "estimate", "haze", "io", "measured", "nn", "sh",
           "models", "operations", "run", "report", "irradiance", "sun_position", "sun_events",
           "__version__"]

QUANTITIES = ("rgb", "xyz", "luminance", "spectral")


def models():
    """The registry's models: the same records as ``skylight models --json``."""
    return _json.loads(_skylight.models_json())


def operations():
    """The library's operations with their parameters: ``skylight operations --json``."""
    return _json.loads(_skylight.operations_json())


class _Text(str):
    """Text given to an operation's text input in memory, instead of the path of a file (e.g. a
    table's JSON)."""


def _argument(value):
    if isinstance(value, _dt.datetime):
        return _iso8601(value)
    return value


def run(operation, progress=None, **arguments):
    """Runs the library's operation ``operation`` (its name as the command line spells it:
    "render", "haze add", "sh fit", ...; ``pyskylight.operations()`` lists them with their
    parameters, relations and result fields) and returns its record as a dict: the fields the
    operation declares, as ``skylight <operation> --json`` prints them.

    ``arguments``: the operation's parameters with ``-`` spelled ``_`` (one that is a Python
    keyword with ``_`` after it: ``from_``; files as paths or path-likes; a time as ISO 8601 text
    or an aware datetime). An image input may be a numpy array (H, W, C) instead of a path. An
    output not given a path is returned in the dict under its name: an image as a float32 array
    (H, W, C), a text as str (bytes where it is not text, e.g. a .npy matrix); an optional output
    not given is not made. The request is checked before
    any work exactly as the command line checks it (the same errors and warnings: warnings are
    ``SkylightWarning``s). ``progress(done, total, step)`` is called between steps (total 0:
    unknown); Ctrl-C stops the operation there (KeyboardInterrupt), writing nothing."""
    kwargs, inputs = {}, {}
    for key, value in arguments.items():
        if key.endswith("_") and _keyword.iskeyword(key[:-1]):
            key = key[:-1]  # a parameter named as a Python keyword (nn animate's from): from_
        if isinstance(value, _np.ndarray):
            a = _np.asarray(value, dtype=_np.float32)
            inputs[key] = a[:, :, None] if a.ndim == 2 else a
        elif isinstance(value, _Text):
            inputs[key] = str(value)
        else:
            kwargs[key] = _argument(value)
    record, outputs = _skylight.run_operation(operation, kwargs, inputs, progress)
    result = _json.loads(record)
    result.update(outputs)
    return result


def report(output_dir, progress=None, **options):
    """Writes the validation and comparison report (the ``report`` operation: index.html,
    figures, report.json) into ``output_dir`` (created if needed; all files or none) and returns
    its record (``index``, ``files``). ``options``: the operation's (measurements, epw,
    sun_azimuth, sun_elevation, quick; ``pyskylight.operations()``)."""
    return run("report", progress=progress, output=output_dir, **options)


def irradiance(model, tilt=0.0, surface_azimuth=180.0, epw=None, progress=None, **parameters):
    """The light of a sky on planes: the ``irradiance`` operation (docs/IRRADIANCE.md) over arrays
    of planes. ``tilt`` and ``surface_azimuth`` [deg] may be arrays of any shape (broadcast
    together); ``parameters``: the model's and the operation's (transposition, albedo, horizon, the
    sun, ...), as ``run`` takes them.

    Without ``epw``, one sky: a dict with each number the record gives (``poa_global_w_m2``,
    ``poa_global_lx``, ``melanopic_edi_lx``, ...; the keys the sky cannot give are left out, and
    ``notes`` says why) as a float64 array of the planes' shape. With ``epw`` (a weather file), every
    hour with the sun up: the hour columns (``record``, ``month``, ``day``, ``hour``,
    ``sun_zenith_deg``, ``sun_azimuth_deg``, ``dni_w_m2``, ``dhi_w_m2``, ``albedo``) as arrays of
    shape (hours,), each plane key as an array of shape planes + (hours,), the year's sums
    (``poa_global_kwh_m2``, ...) of the planes' shape, and ``hours``. Each plane is one call into
    the library (the sky is evaluated again for each)."""
    t, a = _np.broadcast_arrays(_np.asarray(tilt, dtype=_np.float64),
                                _np.asarray(surface_azimuth, dtype=_np.float64))
    records, tables = [], []
    with _tempfile.TemporaryDirectory(prefix="pyskylight-irradiance-") as folder:
        for k, (tk, ak) in enumerate(zip(t.ravel(), a.ravel())):
            args = dict(parameters, model=model, tilt=float(tk), surface_azimuth=float(ak))
            if epw is not None:
                args.update(epw=epw, output=_os.path.join(folder, f"{k}.npy"))
            records.append(run("irradiance", progress=progress, **args))
            if epw is not None:
                tables.append(_np.load(args["output"]))
    first = records[0]
    out = {"notes": first["notes"]} if first.get("notes") is not None else {}
    for key, value in first.items():
        if isinstance(value, (int, float)) and not isinstance(value, bool) and key not in (
                "tilt_deg", "surface_azimuth_deg"):
            out[key] = _np.array([r[key] for r in records], dtype=_np.float64).reshape(t.shape)
    out["tilt_deg"], out["surface_azimuth_deg"] = t.copy(), a.copy()
    if epw is not None:
        columns = first["columns"]
        hour_columns = columns[:columns.index("angle_of_incidence_deg")]
        for j, name in enumerate(columns):
            stacked = _np.stack([table[:, j] for table in tables]).reshape(t.shape + (-1,))
            out[name] = stacked[(0,) * t.ndim] if name in hour_columns else stacked
    return out


def _iso8601(t):
    """A time as the library parses it: ISO 8601 text, or a timezone-aware datetime."""
    if isinstance(t, str):
        return t
    if isinstance(t, _dt.datetime):
        if t.tzinfo is None or t.utcoffset() is None:
            raise InvalidArgument("time: a datetime needs a timezone (tzinfo), e.g. datetime.timezone.utc")
        return t.isoformat(timespec="microseconds" if t.microsecond else "seconds")
    raise InvalidArgument(f"time must be ISO 8601 text or a timezone-aware datetime, got {type(t).__name__}")


def _parameter_doc(p):
    unit = f" [{p['unit']}]" if p["unit"] not in ("", "1") else ""
    if p["kind"] in ("number", "integer", "numbers"):
        rng = f", {p['min']:g} .. {p['max']:g}"
    elif p.get("choices"):
        rng = ", " + "|".join(p["choices"])
    else:
        rng = ""
    if p["required"]:
        default = "required"
    elif p["default"] is None:
        default = f"none ({p['when_absent']})"
    else:
        default = repr(p["default"])
    return f"    {p['name'].replace('-', '_')}{unit}{rng}; default {default}: {p['description']}"


def _sky_doc():
    lines = [
        "A sky of one registered model.",
        "",
        "Sky(model, **parameters): the keyword names are the schema's (``pyskylight.models()``).",
        "Common to every model: sun_zenith or sun_elevation, sun_azimuth [deg]; or time (ISO 8601",
        "text or an aware datetime) with lat, lon [deg] and the SPA's elevation, pressure,",
        "temperature, delta_t; include_sun / sun_only (models with a solar disc).",
        "",
    ]
    for m in models():
        lines.append(f"{m['name']}: {m['description']}")
        for p in m["parameters"]:
            if p["name"] in ("sun-zenith", "sun-azimuth"):
                continue
            lines.append(_parameter_doc(p))
        lines.append("")
    return "\n".join(lines)


class Sky:
    __doc__ = _sky_doc()

    def __init__(self, model, **parameters):
        if "time" in parameters and parameters["time"] is not None:
            parameters["time"] = _iso8601(parameters["time"])
        self._sky = _skylight._Sky(model, parameters)

    @property
    def model(self):
        """The model's name."""
        return self._sky.name

    @property
    def sun_zenith(self):
        """The sun's zenith angle [deg] the sky was built for."""
        return self._sky.sun_zenith

    @property
    def sun_azimuth(self):
        """The sun's azimuth [deg] from north towards east."""
        return self._sky.sun_azimuth

    def parameters(self):
        """The parameters the model read (defaults applied), as ``skylight render`` records them."""
        return self._sky.parameters()

    def domain(self):
        """Where the model stands for these parameters: a list of issues (parameter, validity,
        message, spectral_only); empty when valid."""
        return self._sky.domain()

    def columns(self, quantity="rgb", wavelengths=None):
        """The names of the last axis of evaluate()'s result for the quantity."""
        return self._sky.columns(quantity, _wavelengths(quantity, wavelengths))

    def evaluate(self, zenith_deg, azimuth_deg, quantity="rgb", wavelengths=None, exact=False,
                 threads=None, out=None):
        """The quantity in the directions given by zenith and azimuth angles [deg] (arrays of any
        shape, broadcast together): float64 with the quantity's values on the last axis (rgb:
        linear sRGB; xyz: CIE 1931 XYZ, Y in cd/m^2; luminance: one value; spectral: one per
        wavelength [nm] of ``wavelengths``, W m^-2 sr^-1 nm^-1). ``exact=True`` takes the
        per-direction double-precision path of ``skylight eval`` (bit-equal to it); otherwise
        xyz and luminance of the sky take the batch path (single precision, the models' SIMD
        kernels; each model's documented error bound). ``threads``: worker threads (default the
        library's: SKYLIGHT_THREADS or all cores). ``out``: a C-contiguous float64 array of the
        result's shape to write into (no allocation per call)."""
        z, a = _np.broadcast_arrays(_np.asarray(zenith_deg, dtype=_np.float64),
                                    _np.asarray(azimuth_deg, dtype=_np.float64))
        shape = z.shape
        res = self._sky.evaluate_angles(_np.ascontiguousarray(z).reshape(-1),
                                        _np.ascontiguousarray(a).reshape(-1), quantity,
                                        _wavelengths(quantity, wavelengths), bool(exact),
                                        _threads(threads), out)
        return out if out is not None else res.reshape(shape + (res.shape[1],))

    def evaluate_directions(self, v, quantity="rgb", wavelengths=None, exact=False, threads=None,
                            out=None):
        """The quantity in the directions ``v`` of shape (..., 3): x east, y north, z up (any
        length; normalised), as evaluate() (``out`` likewise)."""
        v = _np.asarray(v, dtype=_np.float64)
        if v.ndim < 1 or v.shape[-1] != 3:
            raise InvalidArgument(f"directions must have shape (..., 3), got {v.shape}")
        shape = v.shape[:-1]
        res = self._sky.evaluate_directions(_np.ascontiguousarray(v).reshape(-1, 3), quantity,
                                            _wavelengths(quantity, wavelengths), bool(exact),
                                            _threads(threads), out)
        return out if out is not None else res.reshape(shape + (res.shape[1],))

    def evaluate_soa(self, x, y, z, threads=None, out=None):
        """The sky's CIE 1931 XYZ (Y in cd/m^2) on the models' single-precision batch path, with
        no conversion of the input: ``x``, ``y``, ``z`` are 1-D C-contiguous float32 arrays of
        one length holding unit vectors (|v|^2 within 1e-5 of 1; x east, y north, z up).
        Returns a (3, N) float32 array (rows X, Y, Z), or writes into ``out`` of that shape.
        The fastest way to evaluate many directions (docs/PYTHON.md: the float64 arrays of
        evaluate_directions cost the conversion)."""
        return self._sky.evaluate_soa(x, y, z, _threads(threads), out)

    def render(self, width=None, height=None, projection="equirect", quantity="rgb",
               return_mask=False, threads=None, **image):
        """The sky drawn as ``skylight render`` draws it (CPU): an (H, W, 3) float32 array of
        linear sRGB (``quantity="rgb"``; Y = luminance in cd/m^2) or XYZ, row 0 at the top.
        ``image``: the image options of the render operation (lens, fov, north_angle,
        look_elevation, look_azimuth; ``pyskylight.operations()``). ``return_mask=True`` also
        returns the (H, W) bool mask of pixels without a direction (outside a fisheye circle)."""
        image = dict(image, projection=projection, width=width, height=height)
        pixels, mask = self._sky.render(image, quantity, _threads(threads))
        return (pixels, mask) if return_mask else pixels

    def __repr__(self):
        return (f"pyskylight.Sky({self.model!r}, sun_zenith={self.sun_zenith:g}, "
                f"sun_azimuth={self.sun_azimuth:g}, parameters={self.parameters()!r})")


def _wavelengths(quantity, wavelengths):
    if wavelengths is None:
        return []
    return [float(w) for w in _np.atleast_1d(_np.asarray(wavelengths, dtype=_np.float64))]


def _threads(threads):
    if threads is None:
        return 0
    if isinstance(threads, bool) or int(threads) != threads or not 1 <= int(threads) <= 1024:
        raise InvalidArgument(f"threads = {threads!r} is not an integer in [1, 1024]")
    return int(threads)


def _epoch_ns(times):
    """Nanoseconds since 1970-01-01T00:00:00Z of datetime64 values, aware datetimes or ISO text."""
    a = _np.asarray(times)
    if a.dtype.kind == "M":
        return a.astype("datetime64[ns]").astype(_np.int64), a.shape
    flat = []
    for t in a.reshape(-1):
        t = t.item() if hasattr(t, "item") and not isinstance(t, _dt.datetime) else t
        if isinstance(t, str):
            t = _dt.datetime.fromisoformat(t.replace("Z", "+00:00"))
        if not isinstance(t, _dt.datetime) or t.tzinfo is None or t.utcoffset() is None:
            raise InvalidArgument("times: each time must be numpy datetime64 (UTC), an aware "
                                  "datetime or ISO 8601 text with an offset")
        u = t.astimezone(_dt.timezone.utc).replace(tzinfo=None)
        flat.append(_np.datetime64(u, "ns").astype(_np.int64))
    return _np.asarray(flat, dtype=_np.int64), a.shape


def sun_position(times, lat, lon, **spa):
    """The NREL SPA (Reda & Andreas 2004) for each time: (zenith, azimuth) [deg], arrays of the
    times' shape (topocentric, with refraction; azimuth from north towards east).

    ``times``: numpy datetime64 (taken as UTC), timezone-aware datetimes or ISO 8601 text with an
    offset; ``lat``, ``lon`` [deg]; ``spa``: elevation [m], pressure [mbar], temperature [degC],
    delta_t [s] and the other parameters of ``skylight sun`` (``pyskylight.operations()``)."""
    ns, shape = _epoch_ns(times)
    out = _skylight.sun_position(_np.ascontiguousarray(ns.reshape(-1)),
                                 dict(spa, lat=lat, lon=lon))
    return out[:, 0].reshape(shape), out[:, 1].reshape(shape)


def _utc_offset_minutes(utc_offset):
    if utc_offset is None:
        return 0
    if isinstance(utc_offset, str):
        import re
        m = re.fullmatch(r"([+-])(\d\d):(\d\d)", utc_offset)
        if not m:
            raise InvalidArgument(f"utc_offset = {utc_offset!r} is not +HH:MM or -HH:MM")
        sign = 1 if m.group(1) == "+" else -1
        return sign * (int(m.group(2)) * 60 + int(m.group(3)))
    if hasattr(utc_offset, "total_seconds"):
        return int(round(utc_offset.total_seconds() / 60))
    raise InvalidArgument(f"utc_offset = {utc_offset!r}: give +HH:MM text or a timedelta")


def sun_events(times, lat, lon, utc_offset=None, **spa):
    """Sunrise, transit and sunset (SPA App. A.2) on the local calendar date of each time, as
    ``skylight sun`` gives them: a dict of ``sunrise``, ``transit``, ``sunset`` (numpy
    datetime64[ns] arrays of the times' shape, in UTC; NaT where the event does not occur on that
    date) and ``polar`` (str array: "" on a normal day, "polar_day" or "polar_night").

    ``times`` as for sun_position; the local date is taken at ``utc_offset`` (+HH:MM text or a
    timedelta; None: UTC); ``spa``: the SPA's other parameters (elevation, pressure,
    temperature, delta_t, atmos_refract, ...)."""
    ns, shape = _epoch_ns(times)
    events, kinds = _skylight.sun_events(_np.ascontiguousarray(ns.reshape(-1)),
                                         _utc_offset_minutes(utc_offset),
                                         dict(spa, lat=lat, lon=lon))
    out = {name: events[:, k].view("datetime64[ns]").reshape(shape)
           for k, name in enumerate(("sunrise", "transit", "sunset"))}
    out["polar"] = _np.array(["", "polar_day", "polar_night"])[kinds].reshape(shape)
    return out
