#!/usr/bin/env bash
# The report opens in a browser without broken images: writes a quick report with the CLI, loads
# index.html in headless Chromium (Debian package `chromium`, installed by scripts/setup.sh) and
# reads back the page's own check (an inline script that, on load, verifies every <img> and every
# SVG <image> and writes "images ok: N of M; links ok: K of L" into <p id="image-check">, L being
# the in-page links of the contents). Passes only when N = M > 0 and K = L > 0.
# Fails, never skips, when Chromium is missing.
#
# Usage: tests/report_browser_test.sh PATH/TO/skylight
set -euo pipefail
cli="${1:?usage: report_browser_test.sh PATH/TO/skylight}"
browser="$(command -v chromium || true)"
if [ -z "$browser" ]; then
  echo "FAIL: chromium not found on PATH; install the Debian package 'chromium' (scripts/setup.sh does)" >&2
  exit 1
fi
dir="$(mktemp -d "${TMPDIR:-/tmp}/skylight_report_browser.XXXXXX")"
trap 'rm -rf "$dir"' EXIT
"$cli" report --quick -o "$dir/report" >/dev/null
# --virtual-time-budget lets the page's asynchronous image probes finish before the DOM is dumped.
dom="$(timeout 180 "$browser" --headless --no-sandbox --disable-gpu --disable-background-networking \
  --disable-component-update --disable-sync --no-first-run --user-data-dir="$dir/profile" \
  --virtual-time-budget=20000 --dump-dom "file://$dir/report/index.html" 2>"$dir/chromium.log")" || {
  echo "FAIL: chromium exited with an error; its log:" >&2
  tail -20 "$dir/chromium.log" >&2
  exit 1
}
line="$(grep -o '<p id="image-check">[^<]*</p>' <<<"$dom" || true)"
if [[ "$line" =~ \>images\ ok:\ ([0-9]+)\ of\ ([0-9]+)\;\ links\ ok:\ ([0-9]+)\ of\ ([0-9]+)\</p\>$ ]] &&
  [ "${BASH_REMATCH[1]}" = "${BASH_REMATCH[2]}" ] && [ "${BASH_REMATCH[2]}" -gt 0 ] &&
  [ "${BASH_REMATCH[3]}" = "${BASH_REMATCH[4]}" ] && [ "${BASH_REMATCH[4]}" -gt 0 ]; then
  echo "PASS: $line"
  exit 0
fi
echo "FAIL: the page's image check says: ${line:-<p id=\"image-check\"> not found in the dumped DOM}" >&2
exit 1
