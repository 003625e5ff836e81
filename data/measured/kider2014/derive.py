#!/usr/bin/python3
"""Derives the shipped subset of Kider et al. 2014's clear skies (data/measured/kider2014/) from
the full data set (docs/MEASURED.md, "The shipped subset"):

    /usr/bin/python3 data/measured/kider2014/derive.py ../shared/measured/kider2014 data/measured/kider2014

radiance.csv: per capture and sample, the file name's index, azimuth and elevation, the luminance
of the original 1 nm spectrum (683 * trapezoidal integral of L y-bar over 380-780 nm, y-bar from
data/cie_colorimetry/CIE_xyz_1931_2deg.csv: an integration independent of the library's) and the
spectral radiance at 350, 355, ..., 1000 nm (the original 1 nm values at those wavelengths,
unchanged, 6 significant digits). Sample 0 is kept as measured (the reader replaces it).
pyranometer.csv: the readings of the IRRADIANCE file named like a capture (its date and time).
"""
import os
import re
import sys

import numpy as np

NAME = re.compile(r"_-_(\d+)____([0-9.]+)___([0-9.]+)\.asd\.rad\.txt$")
CAPTURE = re.compile(r"^(\d{4})-(\d\d)-(\d\d)___(\d\d)\.(\d\d)\.(\d\d)$")
SUBSET_NM = np.arange(350, 1001, 5)


def main(src, dst):
    here = os.path.dirname(os.path.abspath(__file__))
    cmf = np.loadtxt(os.path.join(here, "..", "..", "cie_colorimetry", "CIE_xyz_1931_2deg.csv"),
                     delimiter=",")
    rows, pyr = [], []
    for date in sorted(os.listdir(src)):
        rad_dir = os.path.join(src, date, "RADIANCE")
        if not os.path.isdir(rad_dir):
            continue
        for cap in sorted(os.listdir(rad_dir)):
            m = CAPTURE.match(cap)
            if not m:
                continue
            for f in sorted(os.listdir(os.path.join(rad_dir, cap))):
                n = NAME.search(f)
                if not n:
                    continue
                d = np.loadtxt(os.path.join(rad_dir, cap, f), skiprows=1)
                nm, L = d[:, 0], d[:, 1]
                vis = (nm >= 380) & (nm <= 780)
                ybar = np.interp(nm[vis], cmf[:, 0], cmf[:, 2])
                lum = 683.0 * np.trapz(L[vis] * ybar, nm[vis])
                sub = np.interp(SUBSET_NM, nm, L)
                assert np.all(np.isin(SUBSET_NM, nm)), f
                rows.append((cap, int(n[1]), n[2], n[3], lum, sub))
            irr = os.path.join(src, date, "IRRADIANCE", "{}.{}.{}.{}.{}.{}.txt".format(*m.groups()))
            if os.path.isfile(irr):
                for line in open(irr):
                    parts = line.split()
                    if len(parts) == 2:
                        pyr.append((cap, parts[0], parts[1]))
    rows.sort(key=lambda r: (r[0], r[1]))
    os.makedirs(dst, exist_ok=True)
    with open(os.path.join(dst, "radiance.csv"), "w") as out:
        out.write("# Kider et al. 2014 clear-sky scans, Ithaca NY, 2013-05-27 (Apache-2.0: LICENSE here;\n")
        out.write("# data/PROVENANCE.md). Derived by data/measured/kider2014/derive.py: spectral radiance\n")
        out.write("# [W m^-2 sr^-1 nm^-1] at every 5th nm of 350-1000; luminance [cd/m^2] of the 1 nm spectrum.\n")
        out.write("capture,index,file_azimuth_deg,elevation_deg,luminance_cd_m2,"
                  + ",".join(str(w) for w in SUBSET_NM) + "\n")
        for cap, i, az, el, lum, sub in rows:
            out.write(f"{cap},{i},{az},{el},{lum:.9g}," + ",".join(f"{v:.6g}" for v in sub) + "\n")
    with open(os.path.join(dst, "pyranometer.csv"), "w") as out:
        out.write("# Kider et al. 2014 pyranometer readings (global horizontal irradiance) during each scan.\n")
        out.write("capture,global_horizontal_w_m2,time\n")
        for cap, v, t in pyr:
            out.write(f"{cap},{v},{t}\n")
    print(f"{len(rows)} samples, {len(pyr)} pyranometer readings")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
