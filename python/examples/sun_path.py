#!/usr/bin/python3
"""The sun's path on the solstices and an equinox at one place (the NREL SPA through
pyskylight.sun_position, vectorised over a day of minutes), drawn with matplotlib.

Usage: PYTHONPATH=build/python /usr/bin/python3 python/examples/sun_path.py OUT.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pyskylight  # noqa: E402

LAT, LON = 48.14, 11.58  # Munich
fig, ax = plt.subplots(figsize=(7, 4))
for day in ("2024-03-20", "2024-06-21", "2024-12-21"):
    t = np.arange(np.datetime64(f"{day}T00:00"), np.datetime64(f"{day}T23:59"),
                  np.timedelta64(5, "m"))
    zenith, azimuth = pyskylight.sun_position(t, lat=LAT, lon=LON)
    up = zenith < 90
    ax.plot(azimuth[up], 90 - zenith[up], label=day)
ax.set_xlabel("azimuth [deg from north towards east]")
ax.set_ylabel("elevation [deg]")
ax.set_title(f"sun path at {LAT} N, {LON} E (UTC times)")
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=100)
print(f"wrote {sys.argv[1]}")
