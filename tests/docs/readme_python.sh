#!/usr/bin/env bash
# The README's Python lines after exactly the main job's build (scripts/test.sh runs this right
# after scripts/build_main.sh, before it builds anything else): every shell block of README.md's
# "## Python" section runs with its quoted outputs checked (tests/docs/run_doc_blocks.sh).
# Usage: tests/docs/readme_python.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="${1:?usage: readme_python.sh SOURCE_DIR BUILD_DIR}"
build="${2:?usage: readme_python.sh SOURCE_DIR BUILD_DIR}"
from=$(grep -n '^## Python$' "$src/README.md" | cut -d: -f1)
to=$(awk -v from="$from" 'NR > from && /^## / {print NR - 1; exit}' "$src/README.md")
[ -n "$from" ] && [ -n "$to" ] || { echo "readme_python: no '## Python' section in README.md" >&2; exit 1; }
SKYLIGHT_DOC_FILES="README.md:$from-$to" bash "$src/tests/docs/run_doc_blocks.sh" "$src" "$build/skylight"
