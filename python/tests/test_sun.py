"""pyskylight.sun_position: vectorised over numpy datetime64 and aware datetimes; bit-equal to the
C++ SPA (`skylight sun --json`) and within 0.01 deg of python3-ephem above 5 deg elevation."""

import datetime as dt
import json
import os
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")


def test_bit_equal_to_the_cli():
    times = ["2003-10-17T19:30:30", "2024-06-21T10:00:00", "1999-12-31T23:59:59"]  # UTC
    z, a = pyskylight.sun_position(np.array(times, dtype="datetime64[ns]"), lat=39.742476,
                                 lon=-105.1786, elevation=1830.14, pressure=820, temperature=11,
                                 delta_t=67)
    for i, t in enumerate(times):
        out = subprocess.run([CLI, "sun", "--time", t + "Z", "--lat", "39.742476", "--lon", "-105.1786",
                              "--elevation", "1830.14", "--pressure", "820", "--temperature", "11",
                              "--delta-t", "67", "--json"], capture_output=True, text=True,
                             check=True).stdout
        j = json.loads(out)
        assert z[i] == j["zenith_deg"] and a[i] == j["azimuth_deg"]


def test_shapes_and_aware_datetimes():
    t = np.arange("2024-03-20T00:00", "2024-03-21T00:00", np.timedelta64(1, "h"),
                  dtype="datetime64[ns]").reshape(4, 6)
    z, a = pyskylight.sun_position(t, lat=0.0, lon=0.0)
    assert z.shape == (4, 6) and a.shape == (4, 6)
    aware = [dt.datetime(2024, 3, 20, 12, tzinfo=dt.timezone.utc),
             dt.datetime(2024, 3, 20, 14, tzinfo=dt.timezone(dt.timedelta(hours=2)))]
    z2, _ = pyskylight.sun_position(aware, lat=0.0, lon=0.0)
    assert z2[0] == z2[1] == z[2, 0]  # the same instant three ways
    assert z2[0] < 3.0  # equinox noon on the equator
    with pytest.raises(pyskylight.InvalidArgument):
        pyskylight.sun_position([dt.datetime(2024, 3, 20, 12)], lat=0.0, lon=0.0)  # naive
    with pytest.raises(pyskylight.InvalidArgument, match="lat = 91"):
        pyskylight.sun_position(t, lat=91.0, lon=0.0)


# The bound (docs/PYTHON.md): the two algorithms agree to 0.01 deg above 5 deg elevation with refraction off.
EPHEM_TOL_DEG = 0.01


def test_agrees_with_ephem():
    ephem = pytest.importorskip("ephem")
    rng = np.random.default_rng(1)
    base = np.datetime64("2000-01-01T00:00", "s")
    secs = rng.integers(0, 30 * 365 * 86400, 300)
    times = base + secs.astype("timedelta64[s]")
    lats = rng.uniform(-60, 60, 300)
    lons = rng.uniform(-180, 180, 300)
    checked = 0
    for t, la, lo in zip(times, lats, lons):
        z, a = pyskylight.sun_position(np.array([t], dtype="datetime64[ns]"), lat=la, lon=lo,
                                     pressure=0.0)
        obs = ephem.Observer()
        obs.lat, obs.lon = np.radians(la), np.radians(lo)
        obs.pressure = 0.0  # no refraction
        obs.date = str(t).replace("T", " ")
        sun = ephem.Sun(obs)
        alt = np.degrees(float(sun.alt))
        if alt < 5.0:
            continue
        checked += 1
        assert abs((90.0 - z[0]) - alt) < EPHEM_TOL_DEG
        daz = (a[0] - np.degrees(float(sun.az)) + 180.0) % 360.0 - 180.0
        assert abs(daz) * np.cos(np.radians(alt)) < EPHEM_TOL_DEG
    assert checked > 100


def test_sun_events_are_the_clis():
    # Munich on the solstice (+02:00), Tromso in polar day and polar night (+01:00 / +02:00).
    cases = [("2024-06-21T12:00:00+02:00", 48.1, 11.6, "+02:00"),
             ("2024-12-21T09:00:00+01:00", 48.1, 11.6, "+01:00"),
             ("2024-06-21T12:00:00+02:00", 69.65, 18.96, "+02:00"),
             ("2024-12-21T12:00:00+01:00", 69.65, 18.96, "+01:00")]
    for when, lat, lon, off in cases:
        ev = pyskylight.sun_events([when], lat, lon, utc_offset=off)
        j = json.loads(subprocess.run([CLI, "sun", "--time", when, "--lat", str(lat), "--lon",
                                       str(lon), "--json"], capture_output=True, text=True,
                                      check=True).stdout)
        assert ev["polar"][0] == (j["polar"] or "")
        for name in ("sunrise", "transit", "sunset"):
            if j[name] is None:
                assert np.isnat(ev[name][0]), (when, name)
                continue
            # The CLI prints local time to the second: the same instant, rounded.
            cli = dt.datetime.fromisoformat(j[name]).astimezone(dt.timezone.utc)
            mine = ev[name][0].astype("datetime64[ms]").item().replace(tzinfo=dt.timezone.utc)
            assert abs((mine - cli).total_seconds()) <= 0.5, (when, name, mine, cli)
    # Shapes, and the transit close to local solar noon at lon 0 on an equinox.
    t = np.array(["2024-03-20T06:00", "2024-09-22T06:00"], dtype="datetime64[ns]").reshape(2, 1)
    ev = pyskylight.sun_events(t, 0.0, 0.0)
    assert ev["transit"].shape == (2, 1)
    noon = t.astype("datetime64[D]") + np.timedelta64(12, "h")
    assert np.all(np.abs(ev["transit"] - noon) < np.timedelta64(15, "m"))
    with pytest.raises(pyskylight.InvalidArgument, match="utc_offset"):
        pyskylight.sun_events(t, 0.0, 0.0, utc_offset="2:00")
