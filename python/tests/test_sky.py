"""pyskylight.Sky against the library: parameters from the schemas, shapes and broadcasting, errors,
and agreement with the CLI (`skylight eval`) on the same inputs."""

import os
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")


def cli_eval(args, rows):
    text = "zenith_deg,azimuth_deg\n" + "".join(f"{z!r},{a!r}\n" for z, a in rows)
    out = subprocess.run([CLI, "eval", *args], input=text, capture_output=True, text=True,
                         check=True).stdout
    lines = out.strip().split("\n")
    return lines[0].split(","), np.array([[float(x) for x in l.split(",")] for l in lines[1:]])


def test_models_are_the_clis_records():
    out = subprocess.run([CLI, "models", "--json"], capture_output=True, text=True, check=True)
    import json
    assert pyskylight.models() == json.loads(out.stdout)
    names = [m["name"] for m in pyskylight.models()]
    assert {"preetham", "hosek", "cie", "perez", "nishita", "nn"} <= set(names)


def test_keywords_are_the_schemas_names_and_parameters_are_read_back():
    sky = pyskylight.Sky("hosek", turbidity=3, albedo=0.3, sun_zenith=40, sun_azimuth=180)
    assert sky.model == "hosek"
    assert sky.sun_zenith == 40.0 and sky.sun_azimuth == 180.0
    assert sky.parameters()["turbidity"] == 3.0
    assert sky.parameters()["albedo"] == 0.3
    assert sky.domain() == []
    # The time and place through the SPA, as `--time --lat --lon`.
    t = pyskylight.Sky("preetham", time="2024-06-21T12:00:00+02:00", lat=48.1, lon=11.6)
    import datetime as dt
    tz = dt.timezone(dt.timedelta(hours=2))
    t2 = pyskylight.Sky("preetham", time=dt.datetime(2024, 6, 21, 12, tzinfo=tz), lat=48.1, lon=11.6)
    assert t.sun_zenith == t2.sun_zenith and t.sun_azimuth == t2.sun_azimuth
    # The SPA's sun for that instant (10:00 UTC), through the same degrees.
    z, a = pyskylight.sun_position([dt.datetime(2024, 6, 21, 10, tzinfo=dt.timezone.utc)],
                                 lat=48.1, lon=11.6)
    assert t.sun_zenith == z[0] and t.sun_azimuth == a[0]
    assert t.parameters() == {"turbidity": 3.0}


@pytest.mark.parametrize("model,kwargs", [
    ("preetham", {"turbidity": 3}),
    ("hosek", {"turbidity": 4, "albedo": 0.2}),
    ("cie", {"cie_type": 12}),
    ("nn", {"turbidity": 3}),
    ("perez", {"dni": 600, "dhi": 120, "day_of_year": 172}),
])
def test_exact_evaluation_is_bit_equal_to_skylight_eval(model, kwargs):
    rows = [(0.0, 0.0), (30.0, 180.0), (60.0, -90.0), (85.0, 45.5), (100.0, 10.0)]
    flags = []
    for k, v in kwargs.items():
        flags += [f"--{k.replace('_', '-')}", str(v)]
    for quantity in ("rgb", "xyz", "luminance"):
        names, expected = cli_eval(["--model", model, "--sun-zenith", "35", "--sun-azimuth", "170",
                                    "--quantity", quantity, *flags], rows)
        sky = pyskylight.Sky(model, sun_zenith=35, sun_azimuth=170, **kwargs)
        got = sky.evaluate([r[0] for r in rows], [r[1] for r in rows], quantity=quantity,
                           exact=True)
        assert names[2:] == sky.columns(quantity)
        # The CLI prints shortest round-trip doubles: equal to the last bit.
        np.testing.assert_array_equal(got, expected[:, 2:])


# The batch path is single precision: each model's documented bound against the scalar path is a
# few 1e-6 relative (tests of the C++ library); 1e-4 leaves room and still catches a wrong path.
BATCH_REL_TOL = 1e-4


def test_shapes_broadcast_and_the_batch_path_agrees_with_the_exact_one():
    sky = pyskylight.Sky("preetham", turbidity=3, sun_zenith=45, sun_azimuth=180)
    z = np.linspace(0, 89, 30).reshape(5, 6)
    a = np.array([0.0, 90.0, 180.0, 270.0, 45.0, 300.0])  # broadcast over the rows
    fast = sky.evaluate(z, a, quantity="xyz")
    exact = sky.evaluate(z, a, quantity="xyz", exact=True)
    assert fast.shape == (5, 6, 3) and fast.dtype == np.float64
    np.testing.assert_allclose(fast, exact, rtol=BATCH_REL_TOL)
    lum = sky.evaluate(10.0, 0.0, quantity="luminance")
    assert lum.shape == (1,)
    # Directions as vectors: (..., 3), any length.
    v = np.stack([np.sin(np.radians(z)) * np.sin(np.radians(a)),
                  np.sin(np.radians(z)) * np.cos(np.radians(a)), np.cos(np.radians(z))], axis=-1)
    byv = sky.evaluate_directions(3.0 * v, quantity="xyz", exact=True)
    np.testing.assert_allclose(byv, exact, rtol=1e-12)
    # Threads change nothing.
    np.testing.assert_array_equal(sky.evaluate(z, a, quantity="xyz", threads=1), fast)


@pytest.mark.parametrize("model,kwargs", [("preetham", {"turbidity": 3}),
                                          ("hosek", {"turbidity": 3, "albedo": 0.3}),
                                          ("nn", {"turbidity": 3})])
def test_float32_soa_is_the_float64_batch_path_and_checks_its_input(model, kwargs):
    sky = pyskylight.Sky(model, sun_zenith=45, sun_azimuth=180, **kwargs)
    rng = np.random.default_rng(5)
    v = rng.normal(size=(40000, 3))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    x, y, z = (np.ascontiguousarray(v[:, k], dtype=np.float32) for k in range(3))
    soa = sky.evaluate_soa(x, y, z)
    assert soa.shape == (3, 40000) and soa.dtype == np.float32
    # The same float directions through the float64 rows: the same kernel, bit for bit.
    rows = sky.evaluate_directions(v, quantity="xyz")
    np.testing.assert_array_equal(soa.T.astype(np.float64), rows)
    out = np.empty((3, 40000), dtype=np.float32)
    assert sky.evaluate_soa(x, y, z, threads=1, out=out) is out
    np.testing.assert_array_equal(out, soa)
    z_long = z.copy()
    z_long[123] *= 1.01
    with pytest.raises(pyskylight.InvalidArgument, match=r"direction 123 = .* not a unit vector"):
        sky.evaluate_soa(x, y, z_long)
    with pytest.raises(pyskylight.InvalidArgument, match=r"x must be a 1-D C-contiguous float32"):
        sky.evaluate_soa(v[:, 0], y, z)
    with pytest.raises(pyskylight.InvalidArgument, match=r"one length"):
        sky.evaluate_soa(x, y, z[:10])
    with pytest.raises(pyskylight.InvalidArgument, match=r"shape \(3, 40000\)"):
        sky.evaluate_soa(x, y, z, out=np.empty((40000, 3), dtype=np.float32))


def test_spectral_and_sun_modes():
    sky = pyskylight.Sky("preetham", turbidity=3, sun_zenith=45, sun_azimuth=180)
    s = sky.evaluate([10, 20], [0, 0], quantity="spectral", wavelengths=[450, 550, 650])
    assert s.shape == (2, 3) and (s > 0).all()
    assert sky.columns("spectral", [450, 550]) == ["L450", "L550"]
    sun = pyskylight.Sky("preetham", turbidity=3, sun_zenith=45, sun_azimuth=180, sun_only=True)
    at_sun = sun.evaluate(45.0, 180.0, quantity="luminance")
    away = sun.evaluate(10.0, 0.0, quantity="luminance")
    assert at_sun[0] > 1e8 and away[0] == 0.0


def test_bad_values_raise_invalid_argument_naming_the_parameter():
    with pytest.raises(pyskylight.InvalidArgument, match=r"turbidity = 100 is outside"):
        pyskylight.Sky("preetham", turbidity=100)
    with pytest.raises(ValueError, match=r"turbidty is not a parameter of Sky or of model "
                                         r"'preetham'; did you mean 'turbidity'\?"):
        pyskylight.Sky("preetham", turbidty=3)
    with pytest.raises(pyskylight.InvalidArgument, match=r"unknown model 'preethm'"):
        pyskylight.Sky("preethm")
    with pytest.raises(pyskylight.InvalidArgument, match=r"turbidity must be a number"):
        pyskylight.Sky("preetham", turbidity="3")
    with pytest.raises(pyskylight.InvalidArgument, match=r"time gives the sun"):
        pyskylight.Sky("preetham", time="2024-06-21T12:00:00Z", lat=1, lon=2, sun_zenith=3)
    sky = pyskylight.Sky("cie", cie_type=7)
    with pytest.raises(pyskylight.InvalidArgument, match=r"zenith_deg\[1\] = 181 is outside"):
        sky.evaluate([0, 181], [0, 0])
    with pytest.raises(pyskylight.InvalidArgument, match=r"spectral"):
        sky.evaluate(0, 0, quantity="spectral", wavelengths=[550])
    with pytest.raises(pyskylight.InvalidArgument, match=r"quantity = 'lum'"):
        sky.evaluate(0, 0, quantity="lum")


def read_pfm(path):
    """A colour PFM (PF, little-endian scale < 0, rows bottom to top) as (H, W, 3) float32."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]


def test_render_is_the_clis_image(tmp_path):
    sky = pyskylight.Sky("hosek", turbidity=3, albedo=0.3, sun_zenith=50, sun_azimuth=120)
    img = sky.render(64, 32)
    assert img.shape == (32, 64, 3) and img.dtype == np.float32
    out = tmp_path / "sky.pfm"
    subprocess.run([CLI, "render", "--model", "hosek", "--turbidity", "3", "--albedo", "0.3",
                    "--sun-zenith", "50", "--sun-azimuth", "120", "--width", "64", "--height", "32",
                    "-o", str(out)], check=True, capture_output=True)
    np.testing.assert_array_equal(img, read_pfm(out))
    # Pixel centres of the equirect layout: theta = pi (row + 0.5) / H, phi = 2 pi (col + 0.5) / W.
    rows, cols = np.mgrid[0:32, 0:64]
    z = 180.0 * (rows + 0.5) / 32
    a = 360.0 * (cols + 0.5) / 64
    up = z < 90
    # XYZ (the image's rgb is converted from the batch XYZ; eval's rgb of hosek is its native
    # RGB fit, docs/MODELS.md).
    exact = sky.evaluate(z[up], a[up], quantity="xyz", exact=True)
    np.testing.assert_allclose(sky.render(64, 32, quantity="xyz")[up], exact, rtol=BATCH_REL_TOL,
                               atol=1e-3)
    # A fisheye image masks the corners outside its circle.
    fish, mask = sky.render(32, 32, projection="fisheye", return_mask=True)
    assert mask[0, 0] and not mask[16, 16]
    with pytest.raises(pyskylight.InvalidArgument, match=r"lense is not a parameter of render; "
                                                       r"did you mean 'lens'\?"):
        sky.render(32, 32, projection="fisheye", lense="equisolid")
