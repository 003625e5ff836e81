"""Neural sky models (Satilmis et al. 2016; Pietras 2023; docs/NN.md): train a network on a
registered model, on HDR sky images or a Pietras network on nishita (the ``nn train`` operation),
then use it as the ``nn`` model (``pyskylight.Sky("nn", weights=path)``) or the ``pietras``
model."""

import os as _os


def train(output, progress=None, **options):
    """Trains a network (the ``nn train`` operation) and writes its weights file to ``output``
    (atomically; nothing when training fails its held-out check or is interrupted); returns the
    operation's record. What is trained:

    * a sky network on ``source`` (any registered model; default the paper's Preetham; the
      paper's protocol): the iterations, training and validation errors and the held-out check;
    * with ``images=LIST`` a sky network on a sequence of HDR sky images (a CSV list
      ``file[,sun_zenith_deg,sun_azimuth_deg][,time][,mask]``, docs/NN.md; their layout:
      projection, lens, fov, ...; lat and lon for rows with a time; kfold; samples per image):
      each image's sun and samples, the cross-validation folds, the held-out captures' check and
      the final errors;
    * with ``network="pietras"|"log3"`` (and ``source="nishita"``) a Pietras network (samples,
      region, init, the planet's options): its weights, iterations and check.

    ``options``: the operation's (``pyskylight.operations()``); one a kind of training does not
    read warns. ``progress(done, total, step)`` as the training goes; Ctrl-C stops it between
    iterations (KeyboardInterrupt)."""
    from . import run
    return run("nn train", progress=progress, output=output, **options)


def load(path, **parameters):
    """The network in the weights file ``path`` as a sky: ``Sky("nn", weights=path, ...)``."""
    from . import Sky
    return Sky("nn", weights=_os.fspath(path), **parameters)


def glsl(path=None):
    """The network of the weights file ``path`` (a sky network or a Pietras network; None: the
    embedded 6-12-3 network) as a GLSL compilation unit with its weights baked in (the ``nn
    export`` operation, docs/GPU.md)."""
    from . import run
    return run("nn export", weights=path)["glsl"]
