"""The documented install: `cmake --install build --component python` puts an importable package
into site-packages under the prefix (here a scratch prefix)."""

import os
import subprocess
import sys

import pytest


def test_cmake_install_into_a_prefix(tmp_path):
    build = os.environ.get("SKYLIGHT_BUILD_DIR")
    rel = os.environ.get("SKYLIGHT_PYTHON_INSTALL_DIR")
    if not build or not rel:
        pytest.skip("run by ctest (SKYLIGHT_BUILD_DIR)")
    subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix",
                    str(tmp_path)], check=True, capture_output=True)
    site = tmp_path / rel
    code = ("import skylight, sys; assert skylight.__file__.startswith(sys.argv[1]); "
            "print(skylight.Sky('cie', cie_type=7).evaluate(0, 0, quantity='luminance')[0] > 0)")
    env = dict(os.environ, PYTHONPATH=str(site))
    out = subprocess.run([sys.executable, "-c", code, str(site)], env=env, check=True,
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.stdout.strip() == "True"
