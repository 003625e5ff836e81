#!/usr/bin/python3
"""Writes data/weather/synthetic_munich.epw: a SYNTHETIC hourly year in the EnergyPlus weather
format (no station measured it), for the tests and the README's example of `skylight daylight
--epw`. Deterministic (fixed seed). Clear-sky irradiance from a simple broadband model (Bird-like
Linke attenuation: DNI = 1367 E0 exp(-0.09 m T_L) with a seasonal Linke turbidity), clouds from a
first-order Markov chain of cloud cover per hour, DNI scaled by (1 - cover)^1.5 and DHI from the
clearness index by Erbs et al. 1982's correlation; dew point and dry bulb as seasonal and daily
sinusoids with noise. Illuminance and zenith-luminance fields are missing (999999 / 9999): a
synthetic year has no measured illuminance.

Usage: /usr/bin/python3 scripts/make_sample_epw.py [OUT]
"""
import math
import random
import sys

LAT, LON, TZ, ELEV = 48.14, 11.58, 1.0, 520.0
YEAR = 2019  # a non-leap year: 8760 records


def sun_zenith_azimuth(doy, hour_local):
    """Solar zenith and azimuth [deg] (Spencer 1971 declination and equation of time)."""
    g = 2 * math.pi * (doy - 1) / 365
    decl = (0.006918 - 0.399912 * math.cos(g) + 0.070257 * math.sin(g) - 0.006758 * math.cos(2 * g)
            + 0.000907 * math.sin(2 * g) - 0.002697 * math.cos(3 * g) + 0.00148 * math.sin(3 * g))
    eot = 229.18 * (0.000075 + 0.001868 * math.cos(g) - 0.032077 * math.sin(g)
                    - 0.014615 * math.cos(2 * g) - 0.040849 * math.sin(2 * g))
    solar_time = hour_local + (4 * (LON - 15 * TZ) + eot) / 60
    h = math.radians(15 * (solar_time - 12))
    lat = math.radians(LAT)
    cz = math.sin(lat) * math.sin(decl) + math.cos(lat) * math.cos(decl) * math.cos(h)
    cz = max(-1.0, min(1.0, cz))
    z = math.acos(cz)
    az = math.atan2(math.sin(h), math.cos(h) * math.sin(lat) - math.tan(decl) * math.cos(lat))
    return math.degrees(z), (math.degrees(az) + 180) % 360


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "data/weather/synthetic_munich.epw"
    rng = random.Random(20261204)
    lines = [
        "LOCATION,Munich (synthetic),BY,DEU,SYNTHETIC skylight scripts/make_sample_epw.py,000000,"
        f"{LAT:.2f},{LON:.2f},{TZ:.1f},{ELEV:.1f}",
        "DESIGN CONDITIONS,0",
        "TYPICAL/EXTREME PERIODS,0",
        "GROUND TEMPERATURES,0",
        "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
        "COMMENTS 1,SYNTHETIC YEAR: not measured. Written by skylight's scripts/make_sample_epw.py "
        "(clear-sky model + Markov clouds); illuminance fields missing",
        "COMMENTS 2,For tests and examples only; see data/weather/PROVENANCE.md",
        "DATA PERIODS,1,1,Data,Tuesday, 1/ 1,12/31",
    ]
    days = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31]
    cover = 0.5
    doy = 0
    for month in range(1, 13):
        for day in range(1, days[month - 1] + 1):
            doy += 1
            for hour in range(1, 25):
                # Cloud cover: a Markov chain towards a seasonal mean (cloudier in winter).
                mean = 0.55 + 0.2 * math.cos(2 * math.pi * (doy - 15) / 365)
                cover = min(1.0, max(0.0, cover + 0.25 * (mean - cover) + rng.gauss(0, 0.18)))
                z, az = sun_zenith_azimuth(doy, hour - 0.5)
                e0 = 1 + 0.033 * math.cos(2 * math.pi * doy / 365)
                dni = dhi = ghi = 0.0
                if z < 89.5:
                    cz = math.cos(math.radians(z))
                    m = 1 / (cz + 0.50572 * (96.07995 - z) ** -1.6364)
                    linke = 3.0 + 1.0 * math.sin(2 * math.pi * (doy - 80) / 365)
                    dni_clear = 1367 * e0 * math.exp(-0.09 * m * linke)
                    dhi_clear = 1367 * e0 * cz * (0.02 + 0.03 * linke) * (0.7 + 0.3 * cz)
                    ghi = (dni_clear * cz + dhi_clear) * (1 - 0.75 * cover ** 3.4)
                    kt = ghi / (1367 * e0 * cz)
                    frac = (1 - 0.09 * kt if kt <= 0.22 else
                            0.9511 - 0.1604 * kt + 4.388 * kt ** 2 - 16.638 * kt ** 3 + 12.336 * kt ** 4
                            if kt <= 0.8 else 0.165)
                    dhi = ghi * frac
                    dni = max(0.0, (ghi - dhi) / cz)
                t_season = 9 - 10 * math.cos(2 * math.pi * (doy - 20) / 365)
                dry = t_season + 4 * math.sin(2 * math.pi * (hour - 9) / 24) + rng.gauss(0, 1)
                dew = min(dry, t_season - 3 + rng.gauss(0, 1.5))
                lines.append(
                    f"{YEAR},{month},{day},{hour},60,?9?9?9?9E0?9?9?9*9*9?9?9?9?9?9?9?9?9*_*9*9*9*9*9,"
                    f"{dry:.1f},{dew:.1f},{min(100, 60 + 30 * cover):.0f},95400,9999,9999,9999,"
                    f"{ghi:.0f},{dni:.0f},{dhi:.0f},999999,999999,999999,9999,"
                    f"180,2.0,{round(10 * cover)},{round(8 * cover)},20.0,77777,9,999999999,"
                    "999,0.0800,0,88,0.20,0.0,1.0")
    with open(out, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
