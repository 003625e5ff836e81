"""Aerial perspective on images with depth (Morales, Oishi & Ikeuchi 2017; docs/HAZE.md): add,
re-target or remove haze as ``skylight haze add|retarget|remove`` does, on numpy arrays."""

import numpy as _np

from . import _skylight


def _apply(name, image, depth, options):
    return _skylight.haze_apply(name, _np.asarray(image, dtype=_np.float32),
                                _np.asarray(depth, dtype=_np.float32), options)


def add(image, depth, **options):
    """Haze of turbidity ``turbidity`` added to the linear (H, W, 3) ``image`` whose pixels lie at
    ``depth`` (H, W) metres (or normalised with ``near``/``far``), eq. 10. ``options``: the haze
    add operation's (turbidity, altitude, variant, camera or camera_csv, the airlight: airlight
    R,G,B, sky_model, or sky with its layout; the image's camera: vfov/hfov, heading, pitch,
    roll; min_transmission; ``skylight.operations()``). Returns (H, W, 3) float32."""
    return _apply("add", image, depth, options)


def retarget(image, depth, **options):
    """The haze of ``turbidity`` re-targeted to ``target_turbidity`` (eq. 26); options as add."""
    return _apply("retarget", image, depth, options)


def remove(image, depth, **options):
    """The haze of ``turbidity`` removed (eq. 10 inverted, Gamma floored at min_transmission)."""
    return _apply("remove", image, depth, options)
