"""Neural sky models (Satilmis et al. 2016; docs/NN.md): train a network on a registered model,
then use it as the ``nn`` model (``skylight.Sky("nn", weights=path)``)."""

import os as _os

from . import _skylight


def train(output, source="preetham", progress=None, **options):
    """Trains a sky network on ``source`` (any registered model) as ``skylight nn train`` does,
    writes its weights file to ``output`` (atomically; nothing when training fails its held-out
    check or is interrupted) and returns the summary (iterations, training and validation
    errors, the check). ``options``: the nn train operation's (seed, hidden, trainer, inputs,
    encoding, iterations, time_limit, starts, start_iterations, max_error, target_scale, suns,
    view_zeniths, view_azimuths; ``skylight.operations()``). ``progress(iteration, mse)`` is
    called after every iteration. Ctrl-C stops training between iterations (KeyboardInterrupt)."""
    return _skylight.nn_train(_os.fspath(output), dict(options, source=source), progress)


def load(path, **parameters):
    """The network in the weights file ``path`` as a sky: ``Sky("nn", weights=path, ...)``."""
    from . import Sky
    return Sky("nn", weights=_os.fspath(path), **parameters)


def glsl(path=None):
    """The network of the weights file ``path`` (a sky network or a Pietras network; None: the
    embedded 6-12-3 network) as a GLSL compilation unit with its weights baked in, as
    ``skylight nn export --glsl`` writes it (docs/GPU.md)."""
    return _skylight.nn_glsl("" if path is None else _os.fspath(path))
