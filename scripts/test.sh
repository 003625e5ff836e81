#!/usr/bin/env bash
# The test command (README): installs what is missing, builds the main job's targets and runs the
# README's Python lines against them, builds `build/` in Release, runs the whole
# ctest suite there (GoogleTest unit + CLI end-to-end tests, the report in headless Chromium, the
# docs' shell blocks) and builds the README's library example against the installed package.
# `--full` (what CI runs, .ci/run) adds the libFuzzer pass (scripts/fuzz.sh, docs/TESTING.md) and
# the suite again under ASan + UBSan (all but the docs' blocks and the browser check). Each phase's wall time is printed at the end.
# Usage: scripts/test.sh [--full]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
full=0
case "${1:-}" in
  "") ;;
  --full) full=1 ;;
  *) echo "usage: scripts/test.sh [--full]" >&2; exit 2 ;;
esac

phases=()
phase_start=0
phase_name=""
begin() {
  end_phase
  phase_name="$1"
  phase_start=$(date +%s)
  echo "== $1"
}
end_phase() {
  if [ -n "$phase_name" ]; then
    phases+=("$(printf '%6d s  %s' $(($(date +%s) - phase_start)) "$phase_name")")
  fi
  phase_name=""
}
summary() {
  local status=$?
  end_phase
  echo "== phases (wall time; exit $status)"
  printf '%s\n' "${phases[@]}"
  exit "$status"
}
trap summary EXIT

# Fills a pass's table cache with Earth's bruneton tables (the default parameters, 4 orders) by the
# pass's own binary, before its tests: no test then pays their precomputation (~40 s under the
# sanitizers, in whichever test came first; docs/TESTING.md).
warm_table_cache() {
  printf 'zenith_deg,azimuth_deg\n0,0\n' |
    SKYLIGHT_TABLE_CACHE="$2" "$1/skylight" eval --model bruneton --quantity luminance >/dev/null
}

begin "setup (packages)"
bash scripts/setup.sh
begin "the main job's build, then the README's Python lines against it"
# Exactly the main job's build first (the CLI and the Python package): the README's Python lines
# must run after it alone, as a new user runs them.
bash scripts/build_main.sh
bash tests/docs/readme_python.sh "$root" "$root/build"
begin "Release build"
bash scripts/build.sh build -DCMAKE_BUILD_TYPE=Release -DSKYLIGHT_BUILD_TESTS=ON -DSKYLIGHT_BUILD_BENCH=ON
begin "Release tests (ctest)"
# The processes of one pass share bruneton's precomputed tables through the table cache
# (io/table_cache.h; Earth's take 4 s in Release, ~40 s under the sanitizers, and a dozen tests'
# processes build them): emptied first, so that every pass computes them with its own code.
rm -rf build/test-table-cache
warm_table_cache build "$root/build/test-table-cache"
SKYLIGHT_TABLE_CACHE="$root/build/test-table-cache" \
  ctest --test-dir build --output-on-failure -j "$(nproc)"
rm -rf build/test-table-cache  # 32 MB per parameter set the tests used (~0.5 GB)
begin "install + find_package(skylight) from a separate project"
rm -rf build/install build/consumer
cmake --install build --prefix build/install >/dev/null
cmake -S tests/consumer -B build/consumer -G Ninja -DCMAKE_PREFIX_PATH="$root/build/install" >/dev/null
cmake --build build/consumer >/dev/null
build/consumer/consumer
# The README's library example (built from README.md by tests/consumer) prints what its comments
# say.
example="$(build/consumer/readme_example)"
echo "$example"
grep -qx 'zenith luminance 7320.4 cd/m^2' <<<"$example"
grep -qxF -- 'turbidity = 100 is outside [1, 64] (model '"'preetham'"')' <<<"$example"
[ "$full" = 1 ] || exit 0

begin "libFuzzer targets, 40000 executions each, fixed seed (docs/TESTING.md)"
# A fixed -seed and a fixed number of executions make the fuzz pass the same on every machine: a
# finding here recurs on rerun, and one CI finds is found here.
SKYLIGHT_FUZZ_RUNS="${SKYLIGHT_FUZZ_RUNS:-40000}" SKYLIGHT_FUZZ_FLAGS="-seed=1 ${SKYLIGHT_FUZZ_FLAGS:-}" \
  bash scripts/fuzz.sh
if [ "${SKYLIGHT_SKIP_SANITIZERS:-0}" != "1" ]; then
  begin "ASan + UBSan build"
  # The page's WebAssembly is Emscripten's build of the same sources: the Release one's is reused.
  bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYLIGHT_SANITIZE=ON -DSKYLIGHT_BUILD_TESTS=ON -DSKYLIGHT_BUILD_BENCH=OFF \
    -DSKYLIGHT_WEB_PREBUILT="$root/build/web/skylight_web.js"
  begin "ASan + UBSan tests (ctest)"
  # Every test but the docs' shell blocks and the report and the viewer in Chromium, which the
  # Release pass runs:
  # they rerun CLI commands the Cli.* tests cover, and took 528 of the pass's 1 789 test-seconds
  # under the sanitizers (docs/TESTING.md, "Build and test time"); nor the edge sweeps of the
  # models with a costly set-up (ModelInfo::costly_setup: 350 test-seconds under ASan; their own
  # tests run here), nor BrunetonCostly.* (three sets of bruneton's tables: 30 s of CPU in
  # Release).
  rm -rf build-asan/test-table-cache
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    warm_table_cache build-asan "$root/build-asan/test-table-cache"
  SKYLIGHT_TABLE_CACHE="$root/build-asan/test-table-cache" \
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$(nproc)" \
      -E '^(Docs|ReportBrowser|ViewerBrowser)\.|^Registry/CostlyEdgeSweeps\.|^BrunetonCostly\.'
  rm -rf build-asan/test-table-cache
fi
