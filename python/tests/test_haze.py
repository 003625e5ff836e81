"""pyskylight.haze on arrays: the CLI's image for the same inputs, and remove(add(x)) = x where the
transmission stays above the floor."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")
DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "haze_scene"
OPTIONS = dict(turbidity=3, camera="canon-eos-5d", sky_model="hosek", sun_zenith=40,
               sun_azimuth=200)
# add then remove in float: relative round-off of a few float steps.
ROUND_TRIP_TOL = 1e-4


def cli_flags(options):
    out = []
    for k, v in options.items():
        out += [f"--{k.replace('_', '-')}", str(v)]
    return out


def test_add_is_the_clis_and_remove_undoes_it(tmp_path):
    image = pyskylight.io.read(DATA / "valley.hdr")
    depth = pyskylight.io.read(DATA / "valley_depth.pfm")[:, :, 0]
    hazy = pyskylight.haze.add(image, depth, **OPTIONS)
    assert hazy.shape == image.shape and hazy.dtype == np.float32
    out = tmp_path / "hazy.pfm"
    subprocess.run([CLI, "haze", "add", "--image", str(DATA / "valley.hdr"), "--depth",
                    str(DATA / "valley_depth.pfm"), *cli_flags(OPTIONS), "-o", str(out)],
                   check=True, capture_output=True)
    np.testing.assert_array_equal(hazy, pyskylight.io.read(out))
    # Haze brightens the distant dark ridges; removing it gives the image back where the
    # transmission is well above the floor (the near ridges).
    near = depth < 3000
    back = pyskylight.haze.remove(hazy, depth, **OPTIONS)
    np.testing.assert_allclose(back[near], image[near], rtol=ROUND_TRIP_TOL, atol=1e-3)
    # Re-targeting T 3 -> 2 -> 3 gives the image back (eq. 26 is invertible where the
    # transmission stays above the floor). (3 -> 2 is not add at T 2: eq. 26 scales by the ratio
    # of camera-integrated transmissions, an approximation of the spectral integral; docs/HAZE.md.)
    clearer = pyskylight.haze.retarget(hazy, depth, target_turbidity=2, **OPTIONS)
    again = pyskylight.haze.retarget(clearer, depth, **dict(OPTIONS, turbidity=2, target_turbidity=3))
    np.testing.assert_allclose(again[near], hazy[near], rtol=ROUND_TRIP_TOL, atol=1e-3)


def test_errors():
    image = np.ones((4, 4, 3), np.float32)
    with pytest.raises(pyskylight.InvalidArgument, match="turbidty is not a parameter of haze add"):
        pyskylight.haze.add(image, np.ones((4, 4)), turbidty=3)
    with pytest.raises(pyskylight.InvalidArgument, match="the image has one channel"):
        pyskylight.haze.add(image[:, :, 0], np.ones((4, 4)), **OPTIONS)


def test_composite_is_the_clis(tmp_path):
    background = pyskylight.haze.add(pyskylight.io.read(DATA / "valley.hdr"),
                                   pyskylight.io.read(DATA / "valley_depth.pfm")[:, :, 0], **OPTIONS)
    h, w = background.shape[:2]
    # A grey box 2 km away in the middle third, its edge half covered.
    obj = np.zeros_like(background)
    depth = np.zeros((h, w), np.float32)
    alpha = np.zeros((h, w), np.float32)
    rows, cols = slice(h // 3, 2 * h // 3), slice(w // 3, 2 * w // 3)
    obj[rows, cols] = 0.2
    depth[rows, cols] = 2000.0
    alpha[rows, cols] = 1.0
    alpha[rows, w // 3] = 0.5
    paths = {k: tmp_path / f"{k}.pfm" for k in ("bg", "obj", "depth", "alpha", "out")}
    pyskylight.io.write(paths["bg"], background)
    pyskylight.io.write(paths["obj"], obj)
    pyskylight.io.write(paths["depth"], depth[:, :, None])
    pyskylight.io.write(paths["alpha"], alpha[:, :, None])
    for with_alpha in (True, False):
        args = ["--object-alpha", str(paths["alpha"])] if with_alpha else []
        subprocess.run([CLI, "haze", "composite", "--background", str(paths["bg"]), "--object",
                        str(paths["obj"]), "--object-depth", str(paths["depth"]), *args,
                        *cli_flags(OPTIONS), "-o", str(paths["out"])],
                       check=True, capture_output=True)
        py = pyskylight.haze.composite(background, obj, depth, alpha if with_alpha else None,
                                     **OPTIONS)
        np.testing.assert_array_equal(py, pyskylight.io.read(paths["out"]))
        paths["out"].unlink()
    # Outside the object the background is untouched; inside, the object got the haze add gives.
    py = pyskylight.haze.composite(background, obj, depth, alpha, **OPTIONS)
    np.testing.assert_array_equal(py[alpha == 0], background[alpha == 0])
    hazed = pyskylight.haze.add(obj, np.where(depth > 0, depth, 1.0), **OPTIONS)
    inside = alpha == 1
    np.testing.assert_allclose(py[inside], hazed[inside], rtol=ROUND_TRIP_TOL)
    with pytest.raises(pyskylight.InvalidArgument, match="alpha"):
        pyskylight.haze.composite(background, obj, depth, alpha * 2, **OPTIONS)
