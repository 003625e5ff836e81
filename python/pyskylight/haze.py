"""Aerial perspective on images with depth (Morales, Oishi & Ikeuchi 2017; docs/HAZE.md): add,
re-target or remove haze, or composite a virtual object into a hazy photo, on numpy arrays: the
``haze add|retarget|remove|composite`` operations with the images in memory."""

import numpy as _np


def _image(a):
    return a if isinstance(a, str) or hasattr(a, "__fspath__") else _np.asarray(a, _np.float32)


def _apply(name, image, depth, options):
    from . import run
    return run("haze " + name, image=_image(image), depth=_image(depth), **options)["output"]


def add(image, depth, **options):
    """Haze of turbidity ``turbidity`` added to the linear (H, W, 3) ``image`` whose pixels lie at
    ``depth`` (H, W) metres (or normalised with ``near``/``far``), eq. 10. ``options``: the haze
    add operation's (turbidity, altitude, variant, camera or camera_csv, the airlight: airlight
    R,G,B, sky_model, or sky with its layout; the image's camera: vfov/hfov, heading, pitch,
    roll; min_transmission; ``pyskylight.operations()``). Returns (H, W, 3) float32."""
    return _apply("add", image, depth, options)


def retarget(image, depth, **options):
    """The haze of ``turbidity`` re-targeted to ``target_turbidity`` (eq. 26); options as add."""
    return _apply("retarget", image, depth, options)


def remove(image, depth, **options):
    """The haze of ``turbidity`` removed (eq. 10 inverted, Gamma floored at min_transmission)."""
    return _apply("remove", image, depth, options)


def composite(background, obj, depth, alpha=None, **options):
    """The virtual object ``obj`` ((H, W, 3) linear) at ``depth`` ((H, W) metres, or normalised
    with ``near``/``far``) given the haze of ``turbidity`` (eq. 10, as add) and laid over the
    ``background`` photo, which already shows that haze: alpha * hazed object + (1 - alpha) *
    background (Morales 2017 §6.2). ``alpha``: (H, W) coverage in [0, 1]; None: 1 where the
    depth is > 0. ``options``: the haze composite operation's (as add). Returns (H, W, 3)
    float32."""
    from . import run
    return run("haze composite", background=_image(background), object=_image(obj),
               object_depth=_image(depth),
               object_alpha=None if alpha is None else _image(alpha), **options)["output"]
