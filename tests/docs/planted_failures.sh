#!/usr/bin/env bash
# The docs test can fail: runs tests/docs/run_doc_blocks.sh on small Markdown files, each with one
# planted stale claim of a kind the docs have held (a removed command, a stale quoted output, a
# synopsis pasted as a command, a command writing into the repository, an output block that no
# longer matches, a table split by a blank line), and requires each run to fail with the message that names it; a correct file
# must pass. ctest: DocsRunner.CatchesPlantedFailures.
# Usage: tests/docs/planted_failures.sh SOURCE_DIR PATH/TO/skylight
set -euo pipefail
src="${1:?usage: planted_failures.sh SOURCE_DIR PATH/TO/skylight}"
cli="${2:?usage: planted_failures.sh SOURCE_DIR PATH/TO/skylight}"
runner="$src/tests/docs/run_doc_blocks.sh"
work="$(mktemp -d "${TMPDIR:-/tmp}/skylight_planted.XXXXXX")"
trap 'rm -rf "$work"' EXIT
failures=0

# check NAME WANT_STATUS EXPECTED_MESSAGE: runs the runner on $work/NAME/README.md (a git tree of
# its own with a data/ folder) and checks its exit status and that stderr holds the message.
check() {
  local name="$1" want="$2" message="$3" dir="$work/$1" status=0
  mkdir -p "$dir/data"
  echo "a file of the tree" >"$dir/data/keep.txt"
  git -C "$dir" init -q
  SKYLIGHT_DOC_FILES=README.md bash "$runner" "$dir" "$cli" >"$dir/out.txt" 2>"$dir/err.txt" ||
    status=$?
  if [ "$want" = 0 ] && [ "$status" != 0 ]; then
    echo "FAIL: $name: the correct file failed (exit $status):" >&2
    cat "$dir/err.txt" >&2
    failures=$((failures + 1))
  elif [ "$want" != 0 ] && [ "$status" = 0 ]; then
    echo "FAIL: $name: the planted failure passed" >&2
    failures=$((failures + 1))
  elif [ -n "$message" ] && ! grep -qF -- "$message" "$dir/err.txt"; then
    echo "FAIL: $name: stderr lacks '$message':" >&2
    cat "$dir/err.txt" >&2
    failures=$((failures + 1))
  else
    echo "ok: $name (exit $status)${message:+: $(grep -F -- "$message" "$dir/err.txt" | head -1)}"
  fi
}

fence='```'
write() { mkdir -p "$work/$1" && cat >"$work/$1/README.md"; }

write correct <<EOF
${fence}sh
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 48.14 --lon 11.58
# => zenith                   28.877203 deg
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 91 --lon 0   # exit 2
./build/skylight render --model cie --width 8 --height 4 -o sky.exr
${fence}
EOF
check correct 0 ""

write removed_command <<EOF
${fence}sh
./build/skylight frobnicate --width 8
${fence}
EOF
check removed_command 1 "exit 2, the docs say 0"

write stale_quote <<EOF
${fence}sh
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 48.14 --lon 11.58
# => zenith                   29.9
${fence}
EOF
check stale_quote 1 "output lacks zenith                   29.9"

write stale_json_quote <<EOF
${fence}sh
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 48.14 --lon 11.58 --json
# "zenith_deg": 28.8772..., "sunset": "2026-06-21T21:00:00+02:00"
${fence}
EOF
check stale_json_quote 1 'output lacks "sunset": "2026-06-21T21:00:00+02:00"'

write stale_output_block <<EOF
${fence}sh
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 48.14 --lon 11.58
${fence}

<!-- doc-test: stdout of \`sun --time\` -->
${fence}text
time                     2026-06-21T12:00:00.000+02:00
julian day               2461212.916667 d
zenith                   30.000000 deg
${fence}
EOF
check stale_output_block 1 "differs from what it prints"

write synopsis <<EOF
${fence}sh
./build/skylight models [--json]
${fence}
EOF
check synopsis 1 "a synopsis in a runnable block"

write writes_into_data <<EOF
<!-- doc-test: skip even a skipped block must be pasteable -->
${fence}sh
./build/skylight render --model cie --width 8 --height 4 -o data/sky.exr
${fence}
EOF
check writes_into_data 1 "writes into the repository's data/"

write changes_the_tree <<EOF
${fence}sh
cd data && skylight render --model cie --width 8 --height 4 -o new.exr
${fence}
EOF
check changes_the_tree 1 "the commands changed the source tree"

write split_table <<EOF
| flag | meaning |
|---|---|
| \`--width\` | image width |

| \`--height\` | image height |

${fence}sh
./build/skylight sun --time 2026-06-21T12:00:00+02:00 --lat 48.14 --lon 11.58
${fence}
EOF
check split_table 1 "README.md:5: a table row after a blank line"

[ "$failures" = 0 ] && echo "all planted failures caught, the correct file passes"
[ "$failures" = 0 ]
