"""Images as numpy arrays: EXR, Radiance HDR and PFM as float32 (H, W, C); PNG as uint8 (H, W, 3).
The library's readers and atomic writers (a file is either untouched or complete)."""

import os as _os

import numpy as _np

from . import _skylight


def read(path, metadata=False):
    """The image at ``path`` (format from the extension): float32 (H, W, 1 or 3) for .exr, .hdr,
    .pfm, uint8 (H, W, 3) for .png; with ``metadata=True`` also the EXR header's string
    attributes as a dict (empty for the other formats)."""
    image, meta = _skylight.read_image(_os.fspath(path))
    return (image, meta) if metadata else image


def write(path, image, metadata=None):
    """Writes ``image`` (float (H, W), (H, W, 1) or (H, W, 3) to .exr/.hdr/.pfm; uint8 (H, W, 3)
    to .png) atomically; ``metadata``: str -> str, stored where the format has room (EXR
    attributes, HDR header lines, PNG text chunks)."""
    image = _np.asarray(image)
    _skylight.write_image(_os.fspath(path), image, dict(metadata or {}))
