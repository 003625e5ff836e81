"""Neural sky models (Satilmis et al. 2016; Pietras 2023; docs/NN.md): train a network on a
registered model, on HDR sky images or a Pietras network on nishita, then use it as the ``nn``
model (``skylight.Sky("nn", weights=path)``) or the ``pietras`` model."""

import os as _os

from . import _skylight


def train(output, source="preetham", progress=None, **options):
    """Trains a network as ``skylight nn train`` does and writes its weights file to ``output``
    (atomically; nothing when training fails its held-out check or is interrupted); returns the
    summary. What is trained:

    * a sky network on ``source`` (any registered model; the paper's protocol): returns the
      iterations, training and validation errors and the held-out check;
    * with ``images=LIST`` a sky network on a sequence of HDR sky images (a CSV list
      ``file[,sun_zenith_deg,sun_azimuth_deg][,time][,mask]``, docs/NN.md; their layout:
      projection, lens, fov, ...; lat and lon for rows with a time; kfold; samples per image):
      returns each image's sun and samples, the cross-validation folds, the held-out captures'
      check and the final errors;
    * with ``network="pietras"|"log3"`` (and ``source="nishita"``) a Pietras network (samples,
      region, init, the planet's options): returns its weights, iterations and check.

    ``options``: the nn train operation's (``skylight.operations()``); one a kind of training
    does not read warns. ``progress(iteration, mse)`` is called after every iteration (a Pietras
    network's iterations counted over its sub-networks). Ctrl-C stops training between
    iterations (KeyboardInterrupt)."""
    if "images" in options:
        if source != "preetham":
            raise _skylight.InvalidArgument("source is not an option of training on images")
        options["images"] = _os.fspath(options["images"])
    else:
        options["source"] = source
    for key in ("init", "mask", "camera_csv"):
        if isinstance(options.get(key), _os.PathLike):
            options[key] = _os.fspath(options[key])
    return _skylight.nn_train(_os.fspath(output), options, progress)


def load(path, **parameters):
    """The network in the weights file ``path`` as a sky: ``Sky("nn", weights=path, ...)``."""
    from . import Sky
    return Sky("nn", weights=_os.fspath(path), **parameters)


def glsl(path=None):
    """The network of the weights file ``path`` (a sky network or a Pietras network; None: the
    embedded 6-12-3 network) as a GLSL compilation unit with its weights baked in, as
    ``skylight nn export --glsl`` writes it (docs/GPU.md)."""
    return _skylight.nn_glsl("" if path is None else _os.fspath(path))
