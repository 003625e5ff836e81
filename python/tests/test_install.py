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
    code = ("import pyskylight, sys; assert pyskylight.__file__.startswith(sys.argv[1]); "
            "print(pyskylight.Sky('cie', cie_type=7).evaluate(0, 0, quantity='luminance')[0] > 0)")
    env = dict(os.environ, PYTHONPATH=str(site))
    out = subprocess.run([sys.executable, "-c", code, str(site)], env=env, check=True,
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.stdout.strip() == "True"


def test_pip_install_builds_with_cmake(tmp_path):
    """`pip install --no-build-isolation .` (here `--target`, reusing the build directory of the
    tests through SKYLIGHT_BUILD_DIR so that it only copies the extension)."""
    build = os.environ.get("SKYLIGHT_BUILD_DIR")
    if not build:
        pytest.skip("run by ctest (SKYLIGHT_BUILD_DIR)")
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    target = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
                    "--no-cache-dir", "--quiet", "--target", str(target), root], check=True,
                   capture_output=True, env=dict(os.environ, SKYLIGHT_BUILD_DIR=build))
    names = sorted(p.name for p in (target / "pyskylight").iterdir())
    assert "py.typed" in names and "__init__.pyi" in names
    assert any(n.startswith("_skylight") and n.endswith(".so") for n in names)
    code = "import pyskylight, sys; assert pyskylight.__file__.startswith(sys.argv[1]); print(len(pyskylight.models()))"
    out = subprocess.run([sys.executable, "-c", code, str(target)], check=True, capture_output=True,
                         text=True, cwd=tmp_path, env=dict(os.environ, PYTHONPATH=str(target)))
    assert int(out.stdout) >= 7


def test_sources_without_the_extension_say_what_to_build(tmp_path):
    """The package's sources on PYTHONPATH before the build (python/ of a fresh checkout): the
    ImportError says the extension is missing and names the command that builds it."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = subprocess.run([sys.executable, "-c", "import pyskylight"], capture_output=True,
                         text=True, cwd=tmp_path, env=dict(os.environ, PYTHONPATH=root))
    assert out.returncode != 0
    last = out.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: pyskylight's extension module pyskylight._skylight is "
                           "not built here"), last
    assert "cmake --build build --target skylight_python" in last
