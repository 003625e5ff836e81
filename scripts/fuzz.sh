#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/, clang) in build-fuzz/ and runs each for SECONDS
# (-max_total_time), one after the other, on a copy of its committed seed corpus; prints the
# executions per target and fails on any crash, sanitizer report or other finding
# (docs/TESTING.md).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (default 10 s, all targets)
# Environment: SKYLIGHT_FUZZ_BUILD  build directory (default build-fuzz)
#              SKYLIGHT_FUZZ_CORPUS a directory that keeps the grown corpus between runs
#                                   (<dir>/<target>/); default: a temporary copy, removed
#              SKYLIGHT_FUZZ_FLAGS  extra libFuzzer flags, e.g. "-max_len=65536"
#              SKYLIGHT_FUZZ_RUNS   run each target for this many executions (-runs) instead of
#                                   SECONDS: with a fixed -seed the same inputs on every machine
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-10}"
[ $# -gt 0 ] && shift
all=(directions_csv sky_scan image_pfm image_exr image_hdr image_png sh_table_json nn_weights_json
  exif camera_calibration camera_csv sequence_list depth_image iso8601 epw kider horizon)
targets=("${@:-${all[@]}}")
build="${SKYLIGHT_FUZZ_BUILD:-$root/build-fuzz}"

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (scripts/setup.sh installs it)" >&2; exit 1; }
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSKYLIGHT_FUZZ=ON -DSKYLIGHT_BUILD_TESTS=OFF -DSKYLIGHT_BUILD_BENCH=OFF -DSKYLIGHT_WEB=OFF >/dev/null
cmake --build "$build" --target skylight_fuzz -j "$(nproc)"

budget="${seconds} s"
[ -n "${SKYLIGHT_FUZZ_RUNS:-}" ] && budget="${SKYLIGHT_FUZZ_RUNS} runs"
artifacts="$build/artifacts"
mkdir -p "$artifacts"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
failed=()
summary=()
for t in "${targets[@]}"; do
  exe="$build/tests/fuzz/fuzz_$t"
  [ -x "$exe" ] || { echo "fuzz: unknown target '$t' (known: ${all[*]})" >&2; exit 1; }
  # The committed corpus stays read-only: the run grows a copy.
  if [ -n "${SKYLIGHT_FUZZ_CORPUS:-}" ]; then
    corpus="$SKYLIGHT_FUZZ_CORPUS/$t"
  else
    corpus="$scratch/$t"
  fi
  mkdir -p "$corpus"
  cp -n "$root/tests/fuzz/corpus/$t/"* "$corpus/"
  if [ -n "${SKYLIGHT_FUZZ_RUNS:-}" ]; then
    flags=(-runs="$SKYLIGHT_FUZZ_RUNS")
  else
    flags=(-max_total_time="$seconds")
  fi
  # One allocation over 256 MB is a finding: the image targets refuse more than 2^20 pixels (12 MB
  # of RGB floats), so only a size taken from the file unchecked asks for that much.
  flags+=(-timeout=25 -rss_limit_mb=2048 -malloc_limit_mb=256 -print_final_stats=1
         -artifact_prefix="$artifacts/$t-")
  dict="$root/tests/fuzz/dict/$t.dict"
  [ -f "$dict" ] && flags+=(-dict="$dict")
  # shellcheck disable=SC2206
  flags+=(${SKYLIGHT_FUZZ_FLAGS:-})
  log="$scratch/$t.log"
  echo "== fuzz_$t ($budget)"
  status=0
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 "$exe" "${flags[@]}" "$corpus" >"$log" 2>&1 || status=$?
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  if [ "$status" -ne 0 ]; then
    tail -n 60 "$log"
    failed+=("$t")
    summary+=("$(printf '%-16s %12s  FAILED (exit %d; reproducer in %s)' "$t" "${runs:-?}" "$status" "$artifacts")")
  else
    summary+=("$(printf '%-16s %12s  ok, corpus %d files' "$t" "${runs:-?}" "$(ls "$corpus" | wc -l)")")
  fi
done
echo "== fuzz summary: target, executions ($budget each)"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]}" >&2
  exit 1
fi
