#!/usr/bin/env python3
"""The pyranometer check of the measured skies' absolute level (docs/MEASURED.md, "Absolute
level"): per capture, the diffuse horizontal irradiance of the scan itself (the 81 directions'
radiance integrated over their band and over the sky, ring by ring), the pyranometer's global
horizontal irradiance, their ratio and the direct normal irradiance the two imply.

    PYTHONPATH=build/python /usr/bin/python3 scripts/measured_pyranometer.py [KIDER_DIR]

Without KIDER_DIR the shipped subset (350-1000 nm); the full set (../shared/measured/kider2014)
gives 350-2500 nm, close to the pyranometer's band. The sky is split into bands at the midpoints
between the scan's rings (elevations 12.1, 33.7, 53.4, 71.9, 90 deg); each band's irradiance is its
ring's mean radiance times pi (sin^2 e_hi - sin^2 e_lo). The scan leaves out the sun's disc; the
circumsolar sky counts as its ring's mean."""
import math
import sys

import numpy as np

from pyskylight import measured


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else None
    captures = measured.load_kider(path)
    suns = {r["name"]: r["sun_zenith_deg"] for r in measured.compare("preetham", kider=path)["captures"]}
    print("capture,band_nm,dhi_scan_w_m2,ghi_pyranometer_w_m2,dhi_over_ghi,implied_dni_w_m2")
    for c in captures:
        wl = np.asarray(c["wavelengths_nm"])
        radiance = np.trapz(np.clip(np.asarray(c["radiance"]), 0.0, None), wl, axis=1)
        elevation = np.round(90.0 - np.asarray(c["zenith_deg"]), 2)
        rings = sorted(set(elevation))
        edges = [0.0] + [(a + b) / 2 for a, b in zip(rings, rings[1:])] + [90.0]
        dhi = 0.0
        for i, ring in enumerate(rings):
            lo, hi = math.radians(edges[i]), math.radians(edges[i + 1])
            dhi += radiance[elevation == ring].mean() * math.pi * (math.sin(hi) ** 2 - math.sin(lo) ** 2)
        ghi = c["global_horizontal_w_m2"]
        band = f"{wl[0]:.0f}-{wl[-1]:.0f}"
        if ghi is None:
            print(f"{c['name']},{band},{dhi:.1f},,,")
            continue
        dni = (ghi - dhi) / math.cos(math.radians(suns[c["name"]]))
        print(f"{c['name']},{band},{dhi:.1f},{ghi:.1f},{dhi / ghi:.3f},{dni:.0f}")


if __name__ == "__main__":
    main()
