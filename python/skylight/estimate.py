"""Turbidity (or another model's fitted parameters) from an HDR sky photo on numpy arrays, as
``skylight estimate`` does (Morales et al. 2017; docs/ESTIMATE.md)."""

import os as _os

import numpy as _np

from . import _skylight


def turbidity(image, mask=None, **options):
    """Fits the estimation model (default Preetham's turbidity; ``model=``) to the linear photo
    ``image``: an (H, W, 3) float array (relative luminance is enough) or the path of an EXR, HDR
    or PFM file. ``options``: the estimate operation's (projection, lens, fov, north_angle,
    calibration; sun_zenith and sun_azimuth, or time with lat and lon, or ``exif=`` the capture's
    JPEG/TIFF/DNG (its EXIF time, GPS place and focal length; ``utc_offset=`` when the camera
    wrote none), else the sun is found in the image; the mask rules; samples, seed, ransac, ...;
    ``skylight.operations()``); ``mask``: (H, W[, 1]) nonzero = sky. Returns the fit: the fitted
    parameters with ``_sigma`` (bootstrap), inlier fraction, residual, the sun used and its
    source ("given", "time", "exif", "image"), and with ``exif=`` what the EXIF held."""
    if isinstance(image, (str, _os.PathLike)):
        from . import io
        image = io.read(image)
    for key in ("exif", "calibration"):
        if isinstance(options.get(key), _os.PathLike):
            options[key] = _os.fspath(options[key])
    image = _np.asarray(image, dtype=_np.float32)
    if mask is not None:
        mask = _np.asarray(mask, dtype=_np.float32)
        if mask.ndim == 2:
            mask = mask[:, :, None]
    if "time" in options and options["time"] is not None:
        from . import _iso8601
        options["time"] = _iso8601(options["time"])
    return _skylight.estimate_fit(image, mask, options)
