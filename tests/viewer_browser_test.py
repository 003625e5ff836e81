#!/usr/bin/python3
"""`skylight view`'s page against the library (docs/VIEWER.md), in headless Chromium.

Writes the page with the CLI, opens index.html?test=1&model=M&<param>=<value>...&sun_zenith=Z&
sun_azimuth=A from file:// in Debian's chromium (WebGL2 through SwiftShader), reads the JSON the
page writes into <pre id="test-result"> (at least 500 pixel centres of a 1024 x 512 float frame
with their directions and luminance, and the frame rate) and evaluates the same directions with
`skylight eval`. Fails unless, per model, the median relative difference is <= 1e-3 and the 99th
percentile <= 1e-2 (issue 47's targets), the page weighs <= 5 MB, and a bad flag writes nothing.
Fails, never skips, when Chromium is missing.

Usage: tests/viewer_browser_test.py PATH/TO/skylight [--only MODEL] [--screenshots DIR]
       [--measure FILE]
"""
import argparse
import base64
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

# The page's samples against `skylight eval` (issue 47): relative luminance difference.
MAX_MEDIAN_RELATIVE = 1e-3
MAX_P99_RELATIVE = 1e-2
# Below this fraction of the frame's largest sample the relative difference is not meaningful
# (float rounding of a near-zero luminance); none of the skies below reaches it above the horizon.
FLOOR_OF_PEAK = 1e-4
MIN_SAMPLES = 500
MAX_PAGE_BYTES = 5 * 1024 * 1024

# Each model with values of its schema and a sun (the test contract's query).
CASES = [
    ("preetham", {"turbidity": "3"}, 40.0, 150.0),
    ("preetham", {"turbidity": "6.5"}, 75.0, 250.0),
    ("hosek", {"turbidity": "4", "albedo": "0.3"}, 55.0, 120.0),
    ("cie", {"cie-type": "7"}, 35.0, 200.0),
    ("cie", {"cie-type": "16"}, 60.0, 90.0),
    ("nn", {"turbidity": "3"}, 50.0, 120.0),
    ("perez", {"perez": "-1,-0.32,10,-3,0.45", "zenith-luminance": "5000"}, 30.0, 180.0),
    ("pietras", {"observer-altitude": "2000"}, 60.0, 100.0),
    ("hillaire", {}, 50.0, 120.0),
    ("bruneton", {}, 45.0, 200.0),
]


def chromium_path():
    browser = shutil.which("chromium")
    if not browser:
        sys.exit("FAIL: chromium not found on PATH; install the Debian package 'chromium' "
                 "(scripts/setup.sh does)")
    return browser


class Browser:
    """Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe):
    the page runs in real time (a virtual time budget would stop the clock the page's frame rate
    and load time are measured with)."""

    def __init__(self, browser, profile):
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()

        def fds():
            os.dup2(to_chrome_r, 3)
            os.dup2(from_chrome_w, 4)

        self.proc = subprocess.Popen(
            [browser, "--headless", "--no-sandbox", "--use-angle=swiftshader",
             "--enable-unsafe-swiftshader", "--disable-background-networking",
             "--disable-component-update", "--disable-sync", "--no-first-run",
             "--user-data-dir=" + profile, "--remote-debugging-pipe", "--window-size=1400,760"],
            pass_fds=(3, 4), preexec_fn=fds,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buffer, self.next_id = b"", 0
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget",
                                 {"targetId": target, "flatten": True})["sessionId"]

    def call(self, method, params=None, session=None):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.to_chrome, json.dumps(msg).encode() + b"\0")
        while True:
            while b"\0" not in self.buffer:
                chunk = os.read(self.from_chrome, 1 << 20)
                if not chunk:
                    sys.exit("FAIL: chromium closed its DevTools pipe")
                self.buffer += chunk
            line, self.buffer = self.buffer.split(b"\0", 1)
            reply = json.loads(line)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    sys.exit("FAIL: DevTools %s: %s" % (method, reply["error"]))
                return reply["result"]

    def page(self, method, params=None):
        return self.call(method, params, self.session)

    def open(self, url, until, timeout=120.0):
        """Loads url and waits (real time) until the JavaScript expression `until` is truthy."""
        self.page("Page.navigate", {"url": url})
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            r = self.page("Runtime.evaluate", {"expression": until, "returnByValue": True})
            if r["result"].get("value"):
                return r["result"]["value"]
            time.sleep(0.1)
        sys.exit("FAIL: %s did not finish within %.0f s" % (url, timeout))

    def screenshot(self, path):
        data = self.page("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))

    def close(self):
        self.proc.kill()
        self.proc.wait()


RESULT = "document.getElementById('test-result').textContent"


def page_result(browser, page, query):
    start = time.monotonic()
    text = browser.open("file://%s/index.html?%s" % (page, query), RESULT)
    seconds = time.monotonic() - start
    result = json.loads(text)
    if "error" in result:
        sys.exit("FAIL: the page says: %s (?%s)" % (result["error"], query))
    result["browser_seconds"] = seconds
    return result


def evaluate(cli, model, values, sun, samples):
    flags = ["--model", model, "--sun-zenith", str(sun[0]), "--sun-azimuth", str(sun[1]),
             "--quantity", "luminance"]
    for k, v in values.items():
        flags += ["--" + k, v]
    rows = "zenith_deg,azimuth_deg\n" + "".join(
        "%.17g,%.17g\n" % (s["zenith_deg"], s["azimuth_deg"]) for s in samples)
    run = subprocess.run([cli, "eval", *flags], input=rows, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("FAIL: skylight eval: " + run.stderr)
    lines = run.stdout.strip().splitlines()[1:]
    return [float(line.split(",")[2]) for line in lines]


def relative(a, b, floor):
    return [abs(x - y) / y for x, y in zip(a, b) if y > floor]


def quantile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(q * (len(s) - 1) + 0.5))]


def check_serve(cli, work):
    """`view --serve 0`: the record names the URL; the server answers the page's files and
    nothing outside the folder; SIGINT stops it."""
    page = os.path.join(work, "served")
    proc = subprocess.Popen([cli, "view", "-o", page, "--no-measured", "--serve", "0", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        text = ""
        while not text.rstrip().endswith("}") or text.count("{") != text.count("}"):
            line = proc.stdout.readline()
            if not line:
                sys.exit("FAIL: view --serve ended before its record")
            text += line
        url = json.loads(text)["url"]
        deadline = time.monotonic() + 10
        while True:
            try:
                with urllib.request.urlopen(url, timeout=5) as r:
                    body = r.read()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)
        with open(os.path.join(page, "index.html"), "rb") as f:
            if body != f.read():
                sys.exit("FAIL: view --serve: / is not index.html")
        for bad in ("../etc/passwd", "nothere.js", "a/b.js"):
            try:
                urllib.request.urlopen(url + bad, timeout=5)
                sys.exit("FAIL: view --serve served " + bad)
            except urllib.error.HTTPError as e:
                if e.code != 404:
                    sys.exit("FAIL: view --serve answered %d for %s" % (e.code, bad))
        print("view --serve: %s serves the page, 404 outside it" % url)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=10)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--only", help="one model of the cases")
    ap.add_argument("--screenshots", help="also save screenshots of the page into this folder")
    ap.add_argument("--measure", help="write the measured numbers as JSON to this file")
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="skylight_viewer.")
    browser = Browser(chromium_path(), os.path.join(work, "profile"))
    try:
        page = os.path.join(work, "page")
        start = time.monotonic()
        subprocess.run([args.cli, "view", "-o", page], check=True, capture_output=True)
        view_seconds = time.monotonic() - start
        size = sum(os.path.getsize(os.path.join(page, f)) for f in os.listdir(page))
        print("view -o: %.2f s, %d bytes in %s" % (view_seconds, size, sorted(os.listdir(page))))
        if size > MAX_PAGE_BYTES:
            sys.exit("FAIL: the page weighs %d bytes (> %d)" % (size, MAX_PAGE_BYTES))
        # A bad flag: a one-line error and nothing written.
        bad = os.path.join(work, "bad")
        run = subprocess.run([args.cli, "view", "-o", bad, "--no-such-flag"], capture_output=True,
                             text=True)
        if run.returncode == 0 or os.path.exists(bad) or len(run.stderr.strip().splitlines()) != 1:
            sys.exit("FAIL: view with a bad flag: exit %d, wrote %s, said %r" %
                     (run.returncode, os.path.exists(bad), run.stderr))
        check_serve(args.cli, work)
        measured = {"view_seconds": view_seconds, "page_bytes": size, "models": []}
        failed = False
        for model, values, zen, az in CASES:
            if args.only and model != args.only:
                continue
            query = "test=1&model=%s&%s&sun_zenith=%g&sun_azimuth=%g" % (
                model, "&".join("%s=%s" % kv for kv in values.items()), zen, az)
            r = page_result(browser, page, query)
            samples = r["samples"]
            ref = evaluate(args.cli, model, values, (zen, az), samples)
            gpu = [s["luminance"] for s in samples]
            floor = FLOOR_OF_PEAK * max(ref)
            rel = relative(gpu, ref, floor)
            lib = relative([s["library_luminance"] for s in samples], ref, floor)
            median, p99 = statistics.median(rel), quantile(rel, 0.99)
            ok = (len(rel) >= MIN_SAMPLES and median <= MAX_MEDIAN_RELATIVE and
                  p99 <= MAX_P99_RELATIVE)
            failed |= not ok
            print("%s %s %s: %d samples, median %.2e, p99 %.2e, max %.2e (page's library: "
                  "max %.2e); %.1f fps at %dx%d on %s; page %.1f s" % (
                      "PASS" if ok else "FAIL", model, values, len(rel), median, p99, max(rel),
                      max(lib), r["fps"], r["width"], r["height"], r["renderer"],
                      r["browser_seconds"]))
            measured["models"].append({"model": model, "values": values, "samples": len(rel),
                                       "median": median, "p99": p99, "max": max(rel),
                                       "library_max": max(lib), "fps": r["fps"],
                                       "load_ms": r["load_ms"], "renderer": r["renderer"]})
        if args.screenshots:
            os.makedirs(args.screenshots, exist_ok=True)
            shots = {
                "viewer_fisheye.png": "model=preetham&turbidity=3&sun_zenith=60&sun_azimuth=135",
                "viewer_split.png": "model=preetham&turbidity=3&sun_zenith=60&sun_azimuth=135"
                                    "&compare=side&model_b=hosek&b.turbidity=3&b.albedo=0.3",
                "viewer_difference.png": "model=preetham&turbidity=3&sun_zenith=60&sun_azimuth=135"
                                         "&compare=difference&model_b=hosek&b.turbidity=3"
                                         "&b.albedo=0.3&projection=equirect",
                "viewer_measured.png": "model=hosek&turbidity=3&sun_zenith=39.3&sun_azimuth=138"
                                       "&display=falsecolour&capture=6",
            }
            for name, query in shots.items():
                out = os.path.join(args.screenshots, name)
                browser.open("file://%s/index.html?%s" % (page, query),
                             "document.getElementById('status').textContent.startsWith('ready')")
                browser.screenshot(out)
                print("screenshot", out)
        if args.measure:
            with open(args.measure, "w") as f:
                json.dump(measured, f, indent=1)
        if failed:
            sys.exit("FAIL: the page differs from skylight eval beyond median %g / p99 %g" %
                     (MAX_MEDIAN_RELATIVE, MAX_P99_RELATIVE))
    finally:
        browser.close()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
