#!/usr/bin/env bash
# The main job's build (scripts/main.sh): the CLI and the Python package (build/skylight,
# build/python/pyskylight) in Release. scripts/test.sh runs it first, exactly so, and then the
# README's Python lines against it (tests/docs/readme_python.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
SKYLIGHT_TARGET="skylight_cli skylight_python" bash scripts/build.sh build -DCMAKE_BUILD_TYPE=Release
