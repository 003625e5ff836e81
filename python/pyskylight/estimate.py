"""Turbidity (or another model's fitted parameters) from an HDR sky photo on numpy arrays: the
``estimate`` operation (Morales et al. 2017; docs/ESTIMATE.md)."""

import numpy as _np


def turbidity(image, mask=None, **options):
    """Fits the estimation model (default Preetham's turbidity; ``model=``) to the linear photo
    ``image``: an (H, W, 3) float array (relative luminance is enough) or the path of an EXR, HDR
    or PFM file. ``options``: the estimate operation's (projection, lens, fov, north_angle,
    calibration; sun_zenith and sun_azimuth, or time with lat and lon, or ``exif=`` the capture's
    JPEG/TIFF/DNG (its EXIF time, GPS place and focal length; ``utc_offset=`` when the camera
    wrote none), else the sun is found in the image; the mask rules; samples, seed, ransac, ...;
    ``pyskylight.operations()``); ``mask``: (H, W[, 1]) nonzero = sky, or a mask file. Returns the
    operation's record: the fitted parameters with ``_sigma`` (bootstrap), inlier fraction,
    residual, the sun used and its source ("given", "time", "exif", "image"), and with ``exif=``
    what the EXIF held."""
    from . import run
    if not isinstance(image, _np.ndarray) and not hasattr(image, "__fspath__") and not isinstance(
            image, str):
        image = _np.asarray(image, dtype=_np.float32)
    if mask is not None and not isinstance(mask, (str, _np.ndarray)) and not hasattr(
            mask, "__fspath__"):
        mask = _np.asarray(mask, dtype=_np.float32)
    return run("estimate", image=image, mask=mask, **options)
