"""pyskylight.measured: the captures as arrays (the shipped subset, from the library and from its
folder alike) and the comparison, equal to the CLI's record."""

import json
import os
import pathlib
import subprocess

import numpy as np

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")
ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_the_shipped_subset_as_arrays():
    captures = pyskylight.measured.load_kider()
    assert len(captures) == 15
    c = captures[0]
    assert c["name"] == "2013-05-27___09.30.00"
    assert c["radiance"].shape == (81, 131)
    assert list(c["index"]) == list(range(81))
    assert c["replaced"][0] and not c["replaced"][1:].any()
    # Sample 0 is the mean of its ring neighbours 1 and 31.
    np.testing.assert_array_equal(c["radiance"][0], 0.5 * (c["radiance"][1] + c["radiance"][31]))
    assert c["zenith_deg"][80] == 0.0
    assert len(c["pyranometer_w_m2"]) == 81
    assert abs(c["global_horizontal_w_m2"] - np.mean(c["pyranometer_w_m2"])) < 1e-9
    assert captures[-1]["global_horizontal_w_m2"] is None
    # The same data read from the folder in the source tree.
    from_folder = pyskylight.measured.load_kider(ROOT / "data" / "measured" / "kider2014")
    for a, b in zip(captures, from_folder):
        np.testing.assert_array_equal(a["radiance"], b["radiance"])
        np.testing.assert_array_equal(a["luminance"], b["luminance"])


def test_compare_equals_the_cli(tmp_path):
    record = pyskylight.measured.compare("preetham", exclude_sun_deg=15)
    cli = subprocess.run([CLI, "measured", "--model", "preetham", "--exclude-sun-deg", "15",
                          "--json"], check=True, capture_output=True, text=True)
    assert record == json.loads(cli.stdout)
    assert len(record["captures"]) == 15
    first = record["captures"][0]
    assert first["parameters"][0]["name"] == "turbidity"
    assert len(first["samples"]) == 81
    # The CSV written by Python is the CLI's byte for byte.
    pyskylight.measured.compare("preetham", exclude_sun_deg=15, output=tmp_path / "p.csv")
    subprocess.run([CLI, "measured", "--model", "preetham", "--exclude-sun-deg", "15", "-o",
                    str(tmp_path / "c.csv")], check=True, capture_output=True)
    assert (tmp_path / "p.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()
