"""pyskylight.sh: projection of a sky, reconstruction, rotation and irradiance, against closed forms
(a uniform upper hemisphere) and invariants (rotations compose, the zenith turn is the matrix's)."""

import numpy as np
import pytest

import pyskylight

# Projections converge to 1e-6 relative (ProjectionOptions::tolerance): a bound on their error.
PROJECTION_TOL = 1e-5


def uniform_sky(lum=1000.0):
    # The Perez form with all coefficients 0 is F = 1: L = Lz everywhere above the horizon.
    return pyskylight.Sky("perez", perez=[0, 0, 0, 0, 0], zenith_luminance=lum, sun_zenith=30)


def test_a_uniform_hemisphere_has_its_closed_form_coefficients():
    lum = 1000.0
    c = pyskylight.sh.project(uniform_sky(lum), bands=4)
    assert c.shape == (16, 3)
    # c00 = L 2 pi Y00 = L sqrt(pi); c10 = L pi sqrt(3 / (4 pi)); c20 = 0 (the integral of P2
    # over [0, 1] vanishes); neutral colour: three equal channels.
    np.testing.assert_allclose(c[0], lum * np.sqrt(np.pi), rtol=PROJECTION_TOL)
    np.testing.assert_allclose(c[2], lum * np.pi * np.sqrt(3 / (4 * np.pi)), rtol=PROJECTION_TOL)
    np.testing.assert_allclose(c[6], 0.0, atol=PROJECTION_TOL * lum)
    # The irradiance of an upward surface is pi L exactly (even bands >= 2 of a hemisphere vanish).
    e = pyskylight.sh.irradiance(c, [0, 0, 1])
    np.testing.assert_allclose(e, np.pi * lum, rtol=PROJECTION_TOL)
    # A downward surface sees only the black ground: 0 up to the truncation's ringing.
    assert abs(pyskylight.sh.irradiance(c, [0, 0, -1])[0]) < 0.05 * np.pi * lum


def test_rotations_compose_and_agree():
    sky = pyskylight.Sky("preetham", turbidity=3, sun_zenith=50, sun_azimuth=120)
    c = pyskylight.sh.project(sky, bands=5)
    a = np.radians(40.0)
    # A turn about the zenith by matrix and by angle (the frame: x east, y north, z up; a turn
    # by +40 deg moves azimuth (from north towards east) by +40 deg: d' = R d).
    rz = np.array([[np.cos(a), np.sin(a), 0], [-np.sin(a), np.cos(a), 0], [0, 0, 1]])
    by_angle = pyskylight.sh.rotate(c, zenith_deg=40.0)
    by_matrix = pyskylight.sh.rotate(c, rz)
    np.testing.assert_allclose(by_matrix, by_angle, atol=1e-9 * np.abs(c).max())
    # g(d) = f(R^T d): the turned function at R d is the original at d.
    d = np.array([[0.3, 0.5, 0.8], [0.9, -0.1, 0.2]])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    np.testing.assert_allclose(pyskylight.sh.evaluate(by_matrix, d @ rz.T), pyskylight.sh.evaluate(c, d),
                               rtol=1e-9, atol=1e-9 * np.abs(c).max())
    # Identity leaves the coefficients; a reflection is refused.
    np.testing.assert_allclose(pyskylight.sh.rotate(c, np.eye(3)), c, atol=1e-12 * np.abs(c).max())
    with pytest.raises(pyskylight.InvalidArgument, match="det -1"):
        pyskylight.sh.rotate(c, np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(pyskylight.InvalidArgument, match="orthogonal"):
        pyskylight.sh.rotate(c, np.ones((3, 3)))


def test_reconstruction_approaches_a_smooth_sky():
    # CIE type 1 (overcast) is smooth: 7 bands reconstruct it within a few percent, least well
    # near the horizon where the black ground's step rings (3.3 % at the zenith, 6.8 % at 80 deg
    # measured; docs/SH.md on truncation).
    sky = pyskylight.Sky("cie", cie_type=1, sun_zenith=40)
    c = pyskylight.sh.project(sky, bands=7, channels="xyz")
    z = np.array([0.0, 30.0, 60.0, 80.0])
    a = np.array([0.0, 90.0, 200.0, 300.0])
    exact = sky.evaluate(z, a, quantity="xyz", exact=True)
    v = np.stack([np.sin(np.radians(z)) * np.sin(np.radians(a)),
                  np.sin(np.radians(z)) * np.cos(np.radians(a)), np.cos(np.radians(z))], axis=-1)
    np.testing.assert_allclose(pyskylight.sh.evaluate(c, v), exact, rtol=0.08)
    with pytest.raises(pyskylight.InvalidArgument, match="bands\\^2"):
        pyskylight.sh.evaluate(np.zeros((5, 3)), v)


# A small table (3 bands, degrees 4 x 2 over T 2.5-4): seconds to fit.
SMALL_FIT = dict(bands=3, degrees=[4, 2], range=[2.5, 4.0], theta_range=[10.0, 60.0])
# The small table reproduces its model's projections within a few % of c_00 (docs/SH.md: the
# fits' error is their degrees'; 17 x 12 tables reach 1e-3).
SMALL_FIT_TOL = 0.03


def flags(options):
    out = []
    for k, v in options.items():
        out += [f"--{k.replace('_', '-')}", ",".join(str(x) for x in v) if isinstance(v, list)
                else str(v)]
    return out


def test_fit_is_the_clis_table_and_reproduces_the_projections(tmp_path):
    import json
    import os
    import subprocess
    calls = []
    table = pyskylight.sh.fit("preetham", progress=lambda done, total, step: calls.append((done, total)),
                            **SMALL_FIT)
    assert calls and calls[-1][0] == calls[-1][1]
    d = table.describe()
    assert d["model"] == "preetham" and d["parameter"] == "turbidity" and d["bands"] == 3
    assert d["degrees"] == (4, 2) and d["tau_range"] == (2.5, 4.0)
    cli = tmp_path / "cli.json"
    subprocess.run([os.environ.get("SKYLIGHT_CLI", "skylight"), "sh", "fit", "--model",
                    "preetham", *flags(SMALL_FIT), "-o", str(cli)], check=True,
                   capture_output=True)
    mine = tmp_path / "py.json"
    table.save(mine)
    assert json.loads(mine.read_text()) == json.loads(cli.read_text())
    again = pyskylight.sh.load_table(mine)
    # Within the fit's error of the model's own projection, at a point between the grid's.
    c = again.coefficients(sun_zenith=33.0, tau=3.3, sun_azimuth=120.0)
    ref = pyskylight.sh.project(pyskylight.Sky("preetham", turbidity=3.3, sun_zenith=33.0,
                                           sun_azimuth=120.0), bands=3, channels="xyz")
    unfiltered = again.coefficients(sun_zenith=33.0, tau=3.3, sun_azimuth=120.0,
                                    ringing_filter=False)
    assert c.shape == (9, 3)
    assert np.abs(unfiltered - ref).max() < SMALL_FIT_TOL * abs(ref[0, 1])
    # The sh model reads the saved table: its reconstruction is the filtered coefficients'.
    sky = pyskylight.Sky("sh", table=str(mine), turbidity=3.3, sun_zenith=33.0, sun_azimuth=120.0)
    v = np.array([[0.3, -0.2, 0.9], [0.0, 0.6, 0.5]])
    np.testing.assert_allclose(sky.evaluate_directions(v, quantity="xyz", exact=True),
                               pyskylight.sh.evaluate(c, v), rtol=1e-5)
    assert "preetham" in again.c_header(name="small")
    rows = again.error(points=[3, 2])["rows"]
    assert len(rows) == 3 * 3 and {r["channel"] for r in rows} == {"X", "Y", "Z"}
    assert all(r["e_mean_worst_percent"] >= r["e_mean_median_percent"] >= 0 for r in rows)
    with pytest.raises(pyskylight.InvalidArgument, match="outside"):
        again.coefficients(sun_zenith=80.0, tau=3.0)
    with pytest.raises(pyskylight.InvalidArgument, match="degres is not a parameter of sh fit"):
        pyskylight.sh.fit("preetham", degres=[4, 2])
    with pytest.raises(OSError):
        pyskylight.sh.load_table(tmp_path / "nope.json")


def test_fit_stops_on_ctrl_c():
    import os
    import signal

    def interrupt(done, total, step):
        if done == 2:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        pyskylight.sh.fit("preetham", progress=interrupt, **SMALL_FIT)
