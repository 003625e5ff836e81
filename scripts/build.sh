#!/usr/bin/env bash
# Configures and builds one build tree.
# Usage: scripts/build.sh BUILD_DIR [extra cmake args...]; SKYLIGHT_TARGET=name builds one target.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir="$1"; shift
cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null
if [ -n "${SKYLIGHT_TARGET:-}" ]; then
  cmake --build "$dir" -j "$(nproc)" --target "$SKYLIGHT_TARGET"
else
  cmake --build "$dir" -j "$(nproc)"
fi
