#!/usr/bin/python3
"""The luminance along the solar vertical (view zenith -90..90 deg through the sun, as the
report's section 5 draws it) of several models with one sun, drawn with matplotlib.

Usage: PYTHONPATH=build/python /usr/bin/python3 python/examples/solar_vertical.py OUT.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pyskylight  # noqa: E402

SUN = dict(sun_zenith=60.0, sun_azimuth=180.0)
SKIES = [("preetham", dict(turbidity=3)), ("hosek", dict(turbidity=3, albedo=0.3)),
         ("cie", dict(cie_type=12)), ("nishita", {})]

signed = np.linspace(-89.5, 89.5, 359)  # < 0: the antisolar side
zenith = np.abs(signed)
azimuth = np.where(signed < 0, 0.0, 180.0)  # the sun is in the south
fig, ax = plt.subplots(figsize=(7, 4))
for name, params in SKIES:
    sky = pyskylight.Sky(name, **SUN, **params)
    ax.semilogy(signed, sky.evaluate(zenith, azimuth, quantity="luminance")[..., 0], label=name)
ax.axvline(SUN["sun_zenith"], color="grey", lw=0.8, ls="--")
ax.set_xlabel("view zenith angle along the solar vertical [deg] (sun at +60)")
ax.set_ylabel("luminance [cd/m²]")
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=100)
print(f"wrote {sys.argv[1]}")
