"""Spherical-harmonics sky lighting on numpy arrays (the library's sh/ and fit/sh_fit.h): a
sky's SH projection, reconstruction, rotation, the ringing filter and diffuse irradiance, and
polynomial tables of the coefficients over the sun and turbidity (fit, load, evaluate, export).
Coefficients are float64 arrays of shape (bands^2, 3), row index(l, m) = l (l + 1) + m, real SH
without the Condon-Shortley phase, azimuth from north towards east (docs/SH.md)."""

import os as _os

import numpy as _np

from . import _skylight


def project(sky, bands=3, channels="rgb", ground_albedo=None, tolerance=1e-6):
    """The SH coefficients of ``sky`` (a pyskylight.Sky; the solar disc excluded) on the upper
    hemisphere, the lower one black or, with ``ground_albedo``, a Lambertian ground lit by the
    sky and the sun. ``channels``: "rgb" (linear sRGB) or "xyz". Raises InvalidArgument when
    the projection does not converge to ``tolerance`` (relative change of any coefficient)."""
    c, converged, nodes = _skylight.sh_project(sky._sky, int(bands), channels, ground_albedo,
                                               float(tolerance))
    if not converged:
        raise _skylight.InvalidArgument(
            f"the SH projection did not converge to {tolerance:g} with {nodes} nodes")
    return c


def _per_direction(c, v, irradiance):
    v = _np.asarray(v, dtype=_np.float64)
    if v.ndim < 1 or v.shape[-1] != 3:
        raise _skylight.InvalidArgument(f"directions must have shape (..., 3), got {v.shape}")
    out = _skylight.sh_per_direction(_np.asarray(c, dtype=_np.float64),
                                     _np.ascontiguousarray(v).reshape(-1, 3), irradiance)
    return out.reshape(v.shape[:-1] + (3,))


def evaluate(c, v):
    """The SH reconstruction in the directions ``v`` (..., 3) -> (..., 3)."""
    return _per_direction(c, v, False)


def irradiance(c, normals):
    """The irradiance E(n) of a surface with normal ``n`` (..., 3) under the radiance ``c``
    (clamped-cosine convolution, Ramamoorthi & Hanrahan 2001) -> (..., 3)."""
    return _per_direction(c, normals, True)


def rotate(c, matrix=None, zenith_deg=None):
    """The coefficients of the function turned by the 3 x 3 rotation ``matrix`` (x east, y
    north, z up; d' = R d), or about the zenith by ``zenith_deg`` degrees."""
    if (matrix is None) == (zenith_deg is None):
        raise _skylight.InvalidArgument("rotate takes a matrix or zenith_deg")
    c = _np.asarray(c, dtype=_np.float64)
    if zenith_deg is not None:
        return _skylight.sh_rotate_about_zenith(c, float(zenith_deg))
    return _skylight.sh_rotate(c, _np.asarray(matrix, dtype=_np.float64))


def ringing_filter(c):
    """Habel et al. 2008 eq. 5: the zonal coefficients damped by sinc(pi l / N)."""
    return _skylight.sh_ringing_filter(_np.asarray(c, dtype=_np.float64))


class Table:
    """An SH polynomial table (Habel et al. 2008 eq. 1; docs/SH.md): per stored coefficient and
    channel a Chebyshev polynomial in the sun zenith and the table's parameter tau (turbidity for
    preetham and hosek). Made by :func:`fit` or :func:`load_table`; the ``sh`` model renders one
    (``pyskylight.Sky("sh", table=path)`` after :meth:`save`)."""

    def __init__(self, table):
        self._table = table

    def describe(self):
        """What the table holds: model, parameter (tau's name or None), channels, bands, degrees,
        sun_zenith_range_deg, tau_range, theta_axis, tau_pieces, ground_albedo,
        coefficient_count."""
        return self._table.describe()

    def coefficients(self, sun_zenith, tau=None, sun_azimuth=0.0, bands=None,
                     ringing_filter=True):
        """The (bands², 3) SH coefficients (row l (l + 1) + m, the table's channels) of the sky
        with the sun at ``sun_zenith`` / ``sun_azimuth`` [deg] and ``tau`` (None: the middle of
        the table's range), rotated to the azimuth (eq. 4) and, unless ``ringing_filter=False``,
        filtered (eq. 5). ``bands``: the first N bands (None: all of the table's). Outside the
        fitted ranges raises InvalidArgument."""
        n = self.describe()["bands"] if bands is None else int(bands)
        return self._table.coefficients(float(sun_zenith), None if tau is None else float(tau),
                                        float(sun_azimuth), n, bool(ringing_filter))

    def save(self, path):
        """Writes the table's JSON file (``skylight sh fit -o``'s format; atomically)."""
        self._table.save(_os.fspath(path))

    def c_header(self, name="skylight_sh_table", monomial=False):
        """The table as a C header (the ``sh export`` operation with ``c_header``): its Chebyshev
        coefficients and, with ``monomial``, the published monomial form."""
        from . import run, _Text
        return run("sh export", c_header=True, name=name, monomial=bool(monomial),
                   table=_Text(self._table.to_json()))["output"]

    def error(self, progress=None, **options):
        """E_mean (eq. 3) and E_max (eq. 2) against converged projections of the table's model,
        per band count and channel, worst and median over the test points: the ``sh error``
        operation's record (``rows``, ``points``, ...). ``options``: points (theta, tau),
        midpoints_only. ``progress(done, total, step)`` between projections; Ctrl-C stops
        (KeyboardInterrupt)."""
        from . import run, _Text
        return run("sh error", progress=progress, table=_Text(self._table.to_json()), **options)

    def __repr__(self):
        d = self.describe()
        return (f"pyskylight.sh.Table(model={d['model']!r}, parameter={d['parameter']!r}, "
                f"bands={d['bands']}, degrees={d['degrees']})")


def fit(model, progress=None, **options):
    """Fits an SH polynomial table to a registered model: the ``sh fit`` operation (its
    converged projections on a grid of suns and tau; the model's fit policy gives tau, its range
    and the table's structure). ``options``: the operation's (bands, degrees, parameter, range,
    theta_range, grid, set, channels, tolerance, theta_axis, tau_pieces, ground_albedo;
    ``pyskylight.operations()``). ``progress(done, total, step)`` after each projection; Ctrl-C
    stops between projections (KeyboardInterrupt). Returns a :class:`Table`."""
    from . import run
    return Table(_skylight._ShTable.from_json(run("sh fit", progress=progress, model=model,
                                                  **options)["output"]))


def load_table(path):
    """The table in the JSON file ``path`` (``skylight sh fit -o``'s format), validated."""
    return Table(_skylight._ShTable.load(_os.fspath(path)))
