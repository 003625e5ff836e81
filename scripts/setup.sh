#!/usr/bin/env bash
# Installs the Debian packages skylight needs, if any is missing (we run as root; uses sudo when
# not root and sudo exists). Safe to run repeatedly: does nothing when all are present.
set -euo pipefail
# chromium: the headless browser test of the report (tests/report_browser_test.sh).
# clang + libclang-rt-14-dev: the libFuzzer targets (scripts/fuzz.sh, docs/TESTING.md).
# EGL/GL + Mesa (llvmpipe) + glslang-tools: the headless GL module gpu/ and its tests (docs/GPU.md).
# ccache: the compiler launcher when present (CMakeLists.txt, SKYLIGHT_CCACHE).
# emscripten: the library compiled to WebAssembly for `skylight view`'s page (web/, docs/VIEWER.md).
# python3-dev, python3-numpy, python3-pytest, pybind11-dev, python3-ephem, python3-matplotlib: the
# Python package, its tests (ephem: the independent solar-position check) and the examples of
# docs/PYTHON.md. python3-dask, python3-distributed, python3-zarr: pyskylight.distributed
# (docs/SCALE.md) and its tests.
PACKAGES=(build-essential cmake ninja-build pkg-config git ccache
  libeigen3-dev libopenexr-dev libimath-dev libstb-dev libcli11-dev libfmt-dev libexif-dev
  nlohmann-json3-dev libhwy-dev libgtest-dev libgmock-dev libbenchmark-dev
  chromium clang libclang-rt-14-dev emscripten
  libegl-dev libgles-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri glslang-tools
  python3-dev python3-numpy python3-pytest pybind11-dev python3-ephem python3-matplotlib
  python3-dask python3-distributed python3-zarr)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "skylight setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "skylight setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
