"""Spherical-harmonics sky lighting on numpy arrays (the library's sh/ and fit/sh_fit.h): a
sky's SH projection, reconstruction, rotation, the ringing filter and diffuse irradiance.
Coefficients are float64 arrays of shape (bands^2, 3), row index(l, m) = l (l + 1) + m, real SH
without the Condon-Shortley phase, azimuth from north towards east (docs/SH.md)."""

import numpy as _np

from . import _skylight


def project(sky, bands=3, channels="rgb", ground_albedo=None, tolerance=1e-6):
    """The SH coefficients of ``sky`` (a skylight.Sky; the solar disc excluded) on the upper
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
