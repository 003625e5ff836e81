"""`irradiance` from Python: perez1990 against an independent implementation of the published
formula (1e-9 relative in every clearness bin, docs/IRRADIANCE.md), and pyskylight.irradiance over
arrays of planes and the hours of a weather file."""
import math
import os

import numpy as np
import pytest

import pyskylight as sk

# Perez et al. 1990 (Solar Energy 44(5)), the irradiance model's F-coefficients, all sites
# composite: f11 f12 f13 f21 f22 f23 per clearness bin, typed here from the published table.
F = [(-0.008, 0.588, -0.062, -0.060, 0.072, -0.022),
     (0.130, 0.683, -0.151, -0.019, 0.066, -0.029),
     (0.330, 0.487, -0.221, 0.055, -0.064, -0.026),
     (0.568, 0.187, -0.295, 0.109, -0.152, -0.014),
     (0.873, -0.392, -0.362, 0.226, -0.462, 0.001),
     (1.132, -1.237, -0.412, 0.288, -0.823, 0.056),
     (1.060, -1.600, -0.359, 0.264, -1.127, 0.131),
     (0.678, -0.327, -0.250, 0.156, -1.377, 0.251)]
EPSILON_EDGES = (1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200)
# The formula's own arithmetic in another order: round-off only (docs/IRRADIANCE.md's bound).
TOLERANCE = 1e-9
EPW = os.path.join(os.path.dirname(__file__), "..", "..", "data", "weather", "synthetic_munich.epw")


def perez1990(dni, dhi, zenith_deg, azimuth_deg, day, tilt_deg, surface_azimuth_deg):
    """The sky diffuse irradiance on the plane and its three terms, from the papers alone:
    epsilon (eq. 1, kappa 1.041, Z in radians), Delta = D m / I0 with Kasten's 1966 air mass and
    I0 = 1367 W/m^2 times Spencer's eccentricity (docs/DAYLIGHT.md, the same inputs as the sky)."""
    z = math.radians(zenith_deg)
    eps = ((dhi + dni) / dhi + 1.041 * z ** 3) / (1 + 1.041 * z ** 3)
    air_mass = 1 / (math.cos(z) + 0.15 * (93.885 - zenith_deg) ** -1.253)
    g = 2 * math.pi * (day - 1) / 365
    i0 = 1367 * (1.00011 + 0.034221 * math.cos(g) + 0.00128 * math.sin(g)
                 + 0.000719 * math.cos(2 * g) + 0.000077 * math.sin(2 * g))
    delta = dhi * air_mass / i0
    b = sum(eps >= e for e in EPSILON_EDGES)
    f11, f12, f13, f21, f22, f23 = F[b]
    f1 = max(0.0, f11 + f12 * delta + f13 * z)
    f2 = f21 + f22 * delta + f23 * z
    beta, az = math.radians(tilt_deg), math.radians(surface_azimuth_deg)
    sun_az = math.radians(azimuth_deg)
    cos_aoi = (math.sin(beta) * math.sin(z) * math.cos(sun_az - az) + math.cos(beta) * math.cos(z))
    a = max(0.0, cos_aoi)
    bb = max(math.cos(z), math.cos(math.radians(85)))
    terms = (dhi * (1 - f1) * (1 + math.cos(beta)) / 2, dhi * f1 * a / bb, dhi * f2 * math.sin(beta))
    if sum(terms) < 0:
        terms = (0.0, 0.0, 0.0)
    return b + 1, sum(terms), terms


# Inputs that land in each of the 8 bins (bin 1: overcast, dni 0; bin 8: clear, high dni).
CASES = [(0, 200, 30), (30, 200, 40), (60, 150, 40), (100, 120, 40), (150, 100, 40),
         (250, 100, 40), (600, 90, 40), (800, 70, 40), (600, 90, 80), (200, 60, 86)]


@pytest.mark.parametrize("dni,dhi,zenith", CASES)
def test_perez1990_matches_the_published_formula(dni, dhi, zenith):
    bins = set()
    for tilt, surface_azimuth in ((0, 180), (30, 180), (90, 200), (60, 90), (120, 0)):
        r = sk.run("irradiance", model="perez", dni=dni, dhi=dhi, sun_zenith=zenith,
                   sun_azimuth=150, day_of_year=172, tilt=tilt, surface_azimuth=surface_azimuth,
                   transposition="perez1990")
        b, total, terms = perez1990(dni, dhi, zenith, 150, 172, tilt, surface_azimuth)
        bins.add(b)
        assert r["bin"] == b
        assert r["poa_sky_diffuse_w_m2"] == pytest.approx(total, rel=TOLERANCE, abs=1e-12)
        for key, value in zip(("isotropic", "circumsolar", "horizon"), terms):
            assert r[f"poa_{key}_w_m2"] == pytest.approx(value, rel=TOLERANCE, abs=1e-12)
        assert r["poa_global_lx"] is None and "irradiance coefficients" in " ".join(r["notes"])
    assert len(bins) == 1


def test_the_cases_reach_every_bin():
    reached = {perez1990(dni, dhi, z, 150, 172, 0, 180)[0] for dni, dhi, z in CASES}
    assert reached == set(range(1, 9))


def test_irradiance_is_vectorised_over_planes():
    tilts = np.array([[0.0, 30.0, 90.0], [45.0, 60.0, 180.0]])
    out = sk.irradiance("perez", tilt=tilts, surface_azimuth=180.0, dni=600, dhi=150,
                        sun_zenith=40, sun_azimuth=150, day_of_year=172)
    assert out["poa_global_w_m2"].shape == tilts.shape
    one = sk.run("irradiance", model="perez", tilt=60.0, surface_azimuth=180.0, dni=600, dhi=150,
                 sun_zenith=40, sun_azimuth=150, day_of_year=172)
    assert out["poa_global_w_m2"][1, 1] == one["poa_global_w_m2"]
    # The horizontal plane's sky is the measured diffuse irradiance; facing down sees no sky.
    assert out["poa_sky_diffuse_w_m2"][0, 0] == pytest.approx(150.0, rel=1e-12)
    assert out["poa_sky_diffuse_w_m2"][1, 2] == 0.0
    assert "melanopic_edi_lx" not in out


def test_irradiance_over_a_weather_file():
    out = sk.irradiance("perez", tilt=[30.0, 90.0], surface_azimuth=180.0, epw=EPW,
                        transposition="perez1990", hours="4000-4100")
    hours = out["record"].shape[0]
    assert hours > 20 and out["poa_global_w_m2"].shape == (2, hours)
    assert "poa_global_lx" not in out  # perez1990: irradiance only
    # The year's sums are the hours' sums (Wh -> kWh).
    np.testing.assert_allclose(out["poa_global_kwh_m2"], out["poa_global_w_m2"].sum(axis=1) / 1000,
                               rtol=1e-12)
