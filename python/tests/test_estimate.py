"""pyskylight.estimate.turbidity on numpy images: the CLI's fit (same code path: equal numbers),
the truth of a rendered sky over seeds and noise, errors."""

import json
import os
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")

# A noiseless rendered Preetham sky: the fit recovers T to the LM tolerance.
EXACT_T_TOL = 1e-6
# 5 % multiplicative noise per pixel: the bootstrap's spread times a few, and no more than 2 %.
NOISY_T_TOL = 0.06


@pytest.fixture(scope="module")
def photo(tmp_path_factory):
    path = tmp_path_factory.mktemp("est") / "sky.exr"
    subprocess.run([CLI, "render", "--model", "preetham", "--turbidity", "3", "--sun-zenith", "50",
                    "--sun-azimuth", "200", "--projection", "fisheye", "--width", "256",
                    "--height", "256", "-o", str(path)], check=True, capture_output=True)
    return path


def test_equals_the_cli(photo):
    out = subprocess.run([CLI, "estimate", "--image", str(photo), "--sun-zenith", "50",
                          "--sun-azimuth", "200", "--seed", "7", "--json"], check=True,
                         capture_output=True, text=True).stdout
    cli = json.loads(out)
    py = pyskylight.estimate.turbidity(pyskylight.io.read(photo), sun_zenith=50, sun_azimuth=200, seed=7)
    for key in ("turbidity", "turbidity_sigma", "inlier_fraction", "residual", "luminance_scale",
                "samples", "sky_pixels", "sun_zenith_deg", "sun_azimuth_deg", "method"):
        assert py[key] == cli[key], key
    assert abs(py["turbidity"] - 3.0) < EXACT_T_TOL


def test_seeds_and_noise(photo):
    img = pyskylight.io.read(photo)
    rng = np.random.default_rng(5)
    for seed in (1, 2, 3):
        noisy = img * rng.lognormal(0.0, 0.05, img.shape[:2])[:, :, None].astype(np.float32)
        fit = pyskylight.estimate.turbidity(noisy, sun_zenith=50, sun_azimuth=200, seed=seed)
        assert abs(fit["turbidity"] - 3.0) < NOISY_T_TOL, (seed, fit)


def test_errors(photo):
    img = pyskylight.io.read(photo)
    with pytest.raises(pyskylight.InvalidArgument, match="sun_zenith needs sun_azimuth"):
        pyskylight.estimate.turbidity(img, sun_zenith=50)
    with pytest.raises(pyskylight.InvalidArgument, match="sampels is not a parameter of estimate; "
                                                       "did you mean 'samples'"):
        pyskylight.estimate.turbidity(img, sampels=100)
    with pytest.raises(pyskylight.InvalidArgument, match="shape"):
        pyskylight.estimate.turbidity(img[0, :, 0])


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXIF = os.path.join(ROOT, "tests", "data", "exif", "capture.jpg")
# tests/data/exif/capture.jpg: 2024-06-21 15:00:00 +02:00 at 48 deg 8' N, 11 deg 34' 30" E, 520 m.
WHEN = {"time": "2024-06-21T15:00:00+02:00", "lat": 48.133333333333333, "lon": 11.575,
        "elevation": 520}


def test_exif_gives_the_sun_as_the_cli(tmp_path):
    path = tmp_path / "sky.exr"
    args = [f"--{k}={v}" for k, v in WHEN.items()]
    subprocess.run([CLI, "render", "--model", "preetham", "--turbidity", "4", *args,
                    "--projection", "fisheye", "--width", "200", "--height", "200", "-o", str(path)],
                   check=True, capture_output=True)
    out = subprocess.run([CLI, "estimate", "--image", str(path), "--exif", EXIF, "--seed", "3",
                          "--json"], check=True, capture_output=True, text=True).stdout
    cli = json.loads(out)
    # The path of the photo, or its array; the EXIF file as str or a path object.
    py = pyskylight.estimate.turbidity(path, exif=EXIF, seed=3)
    by_time = pyskylight.estimate.turbidity(pyskylight.io.read(path), seed=3, **WHEN)
    assert py["sun_source"] == "exif" and by_time["sun_source"] == "time"
    for key in ("turbidity", "sun_zenith_deg", "sun_azimuth_deg", "residual", "samples"):
        assert py[key] == cli[key], key
    assert py["sun_zenith_deg"] == by_time["sun_zenith_deg"]
    assert py["exif"] == cli["exif"]
    assert py["exif"]["camera"] == "SkylightTest Fisheye 8mm"
    assert abs(py["turbidity"] - 4.0) < EXACT_T_TOL * 1e3
    # As the command line: a warning, the value not read (not an error).
    with pytest.warns(pyskylight.SkylightWarning, match="utc_offset is not read without exif"):
        pyskylight.estimate.turbidity(path, utc_offset="+02:00", sun_zenith=40, sun_azimuth=180)
    with pytest.raises(pyskylight.InvalidArgument, match="nope.jpg': no such file"):
        pyskylight.estimate.turbidity(path, exif=tmp_path / "nope.jpg")
