"""pyskylight.io: numpy arrays to and from EXR, HDR, PFM and PNG through the library."""

import os
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")


def test_float_round_trips_and_metadata(tmp_path):
    rng = np.random.default_rng(3)
    img = rng.uniform(0.0, 5000.0, (7, 11, 3)).astype(np.float32)
    for ext in ("exr", "pfm"):
        p = tmp_path / f"a.{ext}"
        pyskylight.io.write(p, img, metadata={"skylight:note": "test"})
        back, meta = pyskylight.io.read(p, metadata=True)
        np.testing.assert_array_equal(back, img)  # 32-bit float formats: exact
        if ext == "exr":
            assert meta["skylight:note"] == "test"
    # RGBE: 8-bit mantissas under one shared exponent, so each channel is within 2^-7 of the
    # pixel's largest channel.
    pyskylight.io.write(tmp_path / "a.hdr", img)
    err = np.abs(pyskylight.io.read(tmp_path / "a.hdr") - img)
    assert (err <= img.max(axis=2, keepdims=True) * 2.0 ** -7).all()
    grey = img[:, :, 0]
    pyskylight.io.write(tmp_path / "g.exr", grey)
    assert pyskylight.io.read(tmp_path / "g.exr").shape == (7, 11, 1)
    png = (img / 5000.0 * 255).astype(np.uint8)
    pyskylight.io.write(tmp_path / "p.png", png)
    np.testing.assert_array_equal(pyskylight.io.read(tmp_path / "p.png"), png)


def test_reads_what_the_cli_writes(tmp_path):
    out = tmp_path / "sky.exr"
    subprocess.run([CLI, "render", "--model", "cie", "--cie-type", "7", "--width", "16",
                    "--height", "8", "-o", str(out)], check=True, capture_output=True)
    img, meta = pyskylight.io.read(out, metadata=True)
    assert img.shape == (8, 16, 3)
    assert meta["skylight:model"] == "cie"
    sky = pyskylight.Sky("cie", cie_type=7)
    np.testing.assert_array_equal(img, sky.render(16, 8))


def test_errors(tmp_path):
    with pytest.raises(OSError, match="cannot read"):
        pyskylight.io.read(tmp_path / "missing.exr")
    with pytest.raises(pyskylight.InvalidArgument, match="unsupported|extension"):
        pyskylight.io.write(tmp_path / "a.jpg", np.zeros((2, 2, 3), np.float32))
    with pytest.raises(pyskylight.InvalidArgument, match="NaN or Inf"):
        pyskylight.io.write(tmp_path / "a.exr", np.full((2, 2, 3), np.nan, np.float32))
    assert not (tmp_path / "a.exr").exists()
    with pytest.raises(pyskylight.InvalidArgument, match="uint8"):
        pyskylight.io.write(tmp_path / "a.png", np.zeros((2, 2, 3), np.float32))
