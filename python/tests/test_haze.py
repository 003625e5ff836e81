"""skylight.haze on arrays: the CLI's image for the same inputs, and remove(add(x)) = x where the
transmission stays above the floor."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import skylight

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
    image = skylight.io.read(DATA / "valley.hdr")
    depth = skylight.io.read(DATA / "valley_depth.pfm")[:, :, 0]
    hazy = skylight.haze.add(image, depth, **OPTIONS)
    assert hazy.shape == image.shape and hazy.dtype == np.float32
    out = tmp_path / "hazy.pfm"
    subprocess.run([CLI, "haze", "add", "--image", str(DATA / "valley.hdr"), "--depth",
                    str(DATA / "valley_depth.pfm"), *cli_flags(OPTIONS), "-o", str(out)],
                   check=True, capture_output=True)
    np.testing.assert_array_equal(hazy, skylight.io.read(out))
    # Haze brightens the distant dark ridges; removing it gives the image back where the
    # transmission is well above the floor (the near ridges).
    near = depth < 3000
    back = skylight.haze.remove(hazy, depth, **OPTIONS)
    np.testing.assert_allclose(back[near], image[near], rtol=ROUND_TRIP_TOL, atol=1e-3)
    # Re-targeting T 3 -> 2 -> 3 gives the image back (eq. 26 is invertible where the
    # transmission stays above the floor). (3 -> 2 is not add at T 2: eq. 26 scales by the ratio
    # of camera-integrated transmissions, an approximation of the spectral integral; docs/HAZE.md.)
    clearer = skylight.haze.retarget(hazy, depth, target_turbidity=2, **OPTIONS)
    again = skylight.haze.retarget(clearer, depth, **dict(OPTIONS, turbidity=2, target_turbidity=3))
    np.testing.assert_allclose(again[near], hazy[near], rtol=ROUND_TRIP_TOL, atol=1e-3)


def test_errors():
    image = np.ones((4, 4, 3), np.float32)
    with pytest.raises(skylight.InvalidArgument, match="turbidty is not a parameter of haze.add"):
        skylight.haze.add(image, np.ones((4, 4)), turbidty=3)
    with pytest.raises(skylight.InvalidArgument, match="shape"):
        skylight.haze.add(image[:, :, 0], np.ones((4, 4)), **OPTIONS)
