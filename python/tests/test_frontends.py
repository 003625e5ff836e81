"""The command line and the Python package are two adapters over the library's operations
(docs/OPERATIONS.md): every operation's bad-input cases run through both must give the same verdict
(error, warning or success), the same warnings and the same message, each front end spelling a
parameter its own way (``--sun-zenith`` / ``sun_zenith``, ``-o`` / ``output``). The cases name
parameters as Python does; the command line gets them as flags."""

import json
import os
import re
import subprocess
import warnings

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "data")

# Files the cases name as "@NAME": made once (an image, a fisheye photo, a depth map, a directions
# list) or the repository's data; any other "@NAME" is a path in the scratch folder that does not
# exist (a missing input, or an output).
FILES = {
    "table": os.path.join(DATA, "sh", "preetham_xyz_7_17_12.json"),
    "log3": os.path.join(DATA, "nn", "log3.json"),
    "epw": os.path.join(DATA, "weather", "synthetic_munich.epw"),
}

CAMERA = dict(turbidity=3, camera="canon-eos-5d", airlight=[1, 1, 1])
HAZE = dict(image="@sky.exr", depth="@depth.pfm", output="@h.exr", **CAMERA)

# (operation, arguments, verdict, expected message (Python's spelling; a part of it), warnings
# expected (parts)). verdict: "error" (a usage error: exit 2, InvalidArgument), "failure" (exit 1,
# OSError or RuntimeError) or "success" (exit 0).
CASES = [
    # render and eval: the model's parameters are the chosen model's.
    ("render", dict(model="preetham", turbidty=3, output="@o.exr"), "error",
     "turbidty is not a parameter of render or of model 'preetham'; did you mean 'turbidity'?",
     []),
    ("render", dict(model="cie", sun_zenith=10, sun_elevation=10, output="@o.exr"), "error",
     "sun_zenith and sun_elevation exclude each other", []),
    ("render", dict(model="pietras", turbidity=5, width=8, height=4, output="@o.exr"), "success",
     None, ["turbidity is not a parameter of model 'pietras'; ignored"]),
    ("render", dict(model="cie", width=8, height=4, output="@o.png", preview="@o.png"), "error",
     "output and preview name the same file", []),
    ("render", dict(model="cie", lat=48, output="@o.exr"), "error", "lat needs time", []),
    ("render", dict(model="cie", lens="equisolid", width=8, height=4, output="@o.exr"), "success",
     None, ["lens not used by projection equirect; ignored"]),
    ("render", dict(model="cie", output="@nodir/o.exr"), "failure", "no directory", []),
    ("render", dict(model="cie", width=8, height=4, output="@o.jpg"), "error",
     "write .exr, .hdr, .pfm or .png", []),
    ("eval", dict(model="preetham", input="@missing.csv"), "error", "missing.csv': no such file",
     []),
    ("eval", dict(model="preetham", input="@dirs.csv", paths=100), "success", None,
     ["paths is not read without reference; ignored"]),
    ("eval", dict(model="cie", quantity="spectral", wavelengths=[500], input="@dirs.csv"),
     "error", "no spectral output", []),
    ("eval", dict(model="preetham", input="@dirs.csv", output="@dirs.csv"), "error",
     "is the input input: an output never overwrites an input", []),
    # estimate
    ("estimate", dict(image="@missing.exr"), "error", "missing.exr': no such file", []),
    ("estimate", dict(image="@fish.exr", sun_zenith=40), "error", "sun_zenith needs sun_azimuth",
     []),
    ("estimate", dict(image="@fish.exr", projection="fisheye", utc_offset="+02:00",
                      sun_zenith=45, sun_azimuth=180, samples=50), "success", None,
     ["utc_offset is not read without exif; ignored"]),
    ("estimate", dict(image="@fish.exr", lat=48), "error", "lat needs time, or exif", []),
    ("estimate", dict(image="@fish.exr", compare="@c.exr"), "error", "write .png", []),
    # measured
    ("measured", dict(model="preetham", exclude_sun_deg=20), "success", None, []),
    ("measured", dict(model="hosek", kider="@missing"), "error", "missing': no such folder", []),
    ("measured", dict(model="preetham", utc_offset="EDT"), "error", "is not a UTC offset", []),
    ("measured", dict(model="perez"), "error", "perez", []),
    ("measured", dict(model="cie", output="@m.txt"), "error", "write .csv", []),
    # sun, daylight
    ("sun", dict(time="2026-06-21T12:00:00+02:00", lat=48, lon=11), "success", None, []),
    ("sun", dict(time="2026-06-21T12:00:00+02:00", lat=91, lon=11), "error",
     "lat = 91 is outside [-90, 90]", []),
    ("sun", dict(lat=48, lon=11), "error", "time is required", []),
    ("daylight", dict(dni=700, dhi=120), "error", "daylight needs the sun", []),
    ("daylight", dict(dni=700, dhi=120, sun_zenith=30, day_of_year=172, patches="tregenza"),
     "success", None, ["patches is not read without epw; ignored"]),
    ("daylight", dict(epw="@epw", output="@m.txt"), "error", "write .csv or .npy", []),
    ("daylight", dict(epw="@epw", dni=700, output="@m.csv"), "success", None,
     ["dni is not read with epw (each record gives it); ignored"]),
    ("daylight", dict(epw="@epw", channels="radiance,melanopic", output="@m.csv"), "error",
     "has no spectrum", []),
    ("daylight", dict(dni=700, dhi=120, sun_zenith=30, day_of_year=172, output="@m.csv"),
     "error", "output needs epw", []),
    # irradiance
    ("irradiance", dict(model="hosek", transposition="perez1990"), "error",
     "perez1990 needs measured irradiance", []),
    ("irradiance", dict(model="perez", dni=600, dhi=150, sun_zenith=40, day_of_year=172, tilt=90),
     "success", None, []),
    ("irradiance", dict(model="perez", epw="@epw", output="@s.csv", sun_zenith=30), "success",
     None, ["sun_zenith is not read with epw (the sun of each record); ignored"]),
    ("irradiance", dict(model="perez", epw="@epw", output="@s.txt"), "error", "write .csv or .npy",
     []),
    ("irradiance", dict(model="hosek", tilt=200), "error", "tilt = 200 is outside [0, 180]", []),
    # bench, report
    ("bench", dict(models=""), "error", "models = '' names no model", []),
    ("bench", dict(turbidity=3), "error", "turbidity is not a parameter of bench", []),
    ("bench", dict(models="nope"), "error", "unknown model 'nope'", []),
    ("report", dict(measurements="@missing.csv", output="@rep"), "error", "no such file", []),
    ("report", dict(kider="@missing", output="@rep"), "error", "missing': no such folder", []),
    ("report", dict(sun_azimuth=10, output="@rep"), "error", "sun_azimuth needs sun_elevation",
     []),
    ("report", dict(write_synthetic_measurements="@syn.csv", quick=True), "error",
     "write_synthetic_measurements and quick exclude each other", []),
    ("report", dict(write_synthetic_measurements="@syn.csv"), "success", None, []),
    ("report", dict(), "error", "report needs output DIR (or write_synthetic_measurements FILE)",
     []),
    # sh
    ("sh fit", dict(model="preetham", degres=[4, 2], output="@t.json"), "error",
     "degres is not a parameter of sh fit; did you mean 'degrees'?", []),
    ("sh fit", dict(output="@t.json"), "error", "model is required", []),
    ("sh fit", dict(model="cie", range=[5, 2], output="@t.json"), "error",
     "a fit in the sun zenith only has no second parameter", []),
    ("sh eval", dict(table="@missing.json"), "error", "no such file", []),
    ("sh eval", dict(table="@table", sun_zenith=30), "success", None, []),
    ("sh eval", dict(table="@table", bands=9), "error", "bands", []),
    ("sh export", dict(table="@table", monomial=True, output="@h.h"), "error",
     "monomial needs c_header", []),
    ("sh export", dict(table="@table", c_header=True, output="@h.h"), "success", None, []),
    ("sh render", dict(table="@table", sphere_size=64, width=16, output="@env.pfm"), "success",
     None, ["sphere_size is not read without sphere; ignored"]),
    ("sh render", dict(output="@env.txt"), "error", "write .exr, .hdr, .pfm or .png", []),
    ("sh error", dict(table="@missing.json"), "error", "no such file", []),
    ("sh error", dict(tabel="@table"), "error", "tabel is not a parameter of sh error; did you "
                                                "mean 'table'?", []),
    # haze
    ("haze coefficients", dict(turbidity=3), "success", None, []),
    ("haze coefficients", dict(turbidity=100), "error", "turbidity = 100 is outside [1, 64]", []),
    ("haze coefficients", dict(), "error", "turbidity is required", []),
    ("haze attenuation", dict(turbidity=3, camera="canon-eos-5d"), "error",
     "distance is required", []),
    ("haze attenuation", dict(turbidity=3, camera="canon-eos-5d", camera_csv="@dirs.csv",
                              distance=100), "error", "camera and camera_csv exclude each other",
     []),
    ("haze cameras", dict(foo=1), "error", "foo is not a parameter of haze cameras", []),
    ("haze cameras", dict(), "success", None, []),
    ("haze add", dict(HAZE, sky_model="preetham"), "error",
     "airlight and sky_model exclude each other", []),
    ("haze add", dict(HAZE, output="@sky.exr"), "error",
     "is the input image: an output never overwrites an input", []),
    ("haze add", dict(HAZE), "success", None, []),
    ("haze add", dict(HAZE, sky_mask="@fish.exr"), "error", "sky_mask needs sky", []),
    ("haze retarget", dict(HAZE), "error", "target_turbidity is required", []),
    ("haze remove", dict(HAZE, vfov=30, hfov=30), "error", "vfov and hfov exclude each other",
     []),
    ("haze composite", dict(background="@sky.exr", object="@sky.exr",
                            object_depth="@missing.pfm", output="@h.exr", **CAMERA), "error",
     "missing.pfm': no such file", []),
    ("haze sky-mask", dict(sky="@fish.exr", output="@mask.exr"), "error", "write .png", []),
    # nn
    ("nn train", dict(iteratons=3, output="@w.json"), "error",
     "iteratons is not a parameter of nn train; did you mean 'iterations'?", []),
    ("nn train", dict(images="@dirs.csv", suns=3, output="@w.json"), "error",
     "images and suns exclude each other", []),
    ("nn train", dict(output="@w.json", log="@w.json"), "error",
     "output and log name the same file", []),
    ("nn train", dict(measured="@missing", output="@w.json"), "error",
     "missing': no such folder", []),
    ("nn train", dict(measured="@missing", source="hosek", output="@w.json"), "error",
     "measured and source exclude each other", []),
    ("nn train", dict(network="log3", source="nishita", log="@l.csv", init="@missing.json",
                      output="@w.json"), "error", "missing.json': no such file",
     ["log is not read with network (a Pietras network keeps no log); ignored"]),
    ("nn validate", dict(weights="@missing.json"), "error", "no such file", []),
    ("nn validate", dict(weights="@log3", samples=0), "error", "samples = 0 is outside", []),
    ("nn export", dict(glsl="@g.glsl", weights="@missing.json"), "error", "no such file", []),
    ("nn export", dict(glsl="@g.glsl"), "success", None, []),
    # view
    ("view", dict(output="@page", no_measured=True), "success", None, []),
    ("view", dict(output="@page", kider="@missing"), "error", "missing': no such folder", []),
    ("view", dict(output="@page", kider="@missing", no_measured=True), "error",
     "kider and no_measured exclude each other", []),
    ("view", dict(), "error", "output", []),
    ("nn animate", dict(weights="@log3", turbidity=3, observer_altitude=100,
                        output="@f_#.exr"), "error",
     "turbidity and observer_altitude exclude each other", []),
    ("nn animate", dict(weights="@log3", output="@f.exr", **{"from": [30, 100], "to": [70, 200]}),
     "error", "'#'", []),
    ("nn study", dict(hiden=[2]), "error", "hiden is not a parameter of nn study; did you mean "
                                          "'hidden'?", []),
    ("nn planet", dict(weights="@missing.json", output="@p.png"), "error", "no such file", []),
]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("inputs")
    paths = dict(FILES)
    for name, args in (("sky.exr", ["--model", "cie", "--width", "32", "--height", "16"]),
                       ("fish.exr", ["--model", "preetham", "--projection", "fisheye",
                                     "--width", "64", "--height", "64"])):
        subprocess.run([CLI, "render", *args, "-o", str(d / name)], check=True,
                       capture_output=True)
        paths[name] = str(d / name)
    pyskylight.io.write(d / "depth.pfm", np.full((16, 32), 1000.0, np.float32))
    paths["depth.pfm"] = str(d / "depth.pfm")
    (d / "dirs.csv").write_text("zenith_deg,azimuth_deg\n0,0\n30,90\n")
    paths["dirs.csv"] = str(d / "dirs.csv")
    return paths


def resolve(arguments, files, scratch):
    out = {}
    for k, v in arguments.items():
        if isinstance(v, str) and v.startswith("@"):
            v = files.get(v[1:], str(scratch / v[1:]))
        out[k] = v
    return out


def cli_args(operation, arguments):
    args = operation.split()
    for k, v in arguments.items():
        flag = "-o" if k == "output" else "--" + k.replace("_", "-")
        if v is True:
            args.append(flag)
        elif v is False:
            continue
        elif isinstance(v, list):
            args += [flag, ",".join(str(x) for x in v)]
        else:
            args += [flag, str(v)]
    return args


def python_spelling(message):
    """A command line message in Python's spelling: --sun-zenith -> sun_zenith, -o -> output."""
    message = re.sub(r"(?<![\w-])--([a-z][a-z0-9-]*)",
                     lambda m: m.group(1).replace("-", "_"), message)
    return re.sub(r"(?<![\w-])-o(?![\w-])", "output", message)


def run_cli(operation, arguments, scratch):
    r = subprocess.run([CLI, *cli_args(operation, arguments)], capture_output=True, text=True,
                       cwd=scratch, stdin=subprocess.DEVNULL)
    warns = [python_spelling(l[len("skylight: warning: "):])
             for l in r.stderr.splitlines() if l.startswith("skylight: warning: ")]
    errors = [l[len("skylight: error: "):] for l in r.stderr.splitlines()
              if l.startswith("skylight: error: ")]
    verdict = {0: "success", 1: "failure", 2: "error"}.get(r.returncode, f"exit {r.returncode}")
    return verdict, python_spelling(errors[0]) if errors else None, warns


def run_python(operation, arguments):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            pyskylight.run(operation, **arguments)
            verdict, message = "success", None
        except pyskylight.InvalidArgument as e:
            verdict, message = "error", str(e)
        except (OSError, RuntimeError) as e:
            verdict, message = "failure", str(e)
    warns = [str(w.message) for w in caught if issubclass(w.category, pyskylight.SkylightWarning)]
    return verdict, message, warns


def test_every_operation_has_cases():
    covered = {c[0] for c in CASES}
    names = {op["name"] for op in pyskylight.operations()}
    assert names - covered == set(), f"operations without a case: {sorted(names - covered)}"


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_both_front_ends_give_the_same_verdict_and_message(case, files, tmp_path):
    operation, arguments, verdict, message, warns = case
    cli_dir, py_dir = tmp_path / "cli", tmp_path / "py"
    cli_dir.mkdir()
    py_dir.mkdir()
    # The same paths for both (a message quotes them); the outputs made by one are removed
    # before the other runs.
    args = resolve(arguments, files, tmp_path)
    cli = run_cli(operation, args, cli_dir)
    for f in tmp_path.iterdir():
        if f.is_file():
            f.unlink()
    py = run_python(operation, args)
    assert cli == py, f"{operation} {arguments}:\n  CLI:    {cli}\n  Python: {py}"
    assert cli[0] == verdict, cli
    if message is not None:
        assert message in cli[1], cli
    assert len(cli[2]) == len(warns) and all(w in got for w, got in zip(warns, cli[2])), cli


def test_outputs_in_memory_are_the_files_the_command_line_writes(files, tmp_path):
    """An output not given a path comes back in the record: an image as the array the command
    line writes (bit for bit, through a PFM), a text output as the text it prints."""
    args = dict(model="hosek", turbidity=4, width=24, height=12, sun_zenith=50)
    subprocess.run([CLI, *cli_args("render", args), "-o", str(tmp_path / "sky.pfm")], check=True,
                   capture_output=True)
    record = pyskylight.run("render", **args)
    assert record["output"].dtype == np.float32 and record["output"].shape == (12, 24, 3)
    assert np.array_equal(record["output"], pyskylight.io.read(tmp_path / "sky.pfm"))
    assert record["zenith_luminance_cd_m2"] > 0 and "preview" not in record
    assert list(tmp_path.iterdir()) == [tmp_path / "sky.pfm"]  # nothing else written
    cli = subprocess.run([CLI, "eval", "--model", "preetham", "--input", files["dirs.csv"]],
                         check=True, capture_output=True, text=True).stdout
    assert pyskylight.run("eval", model="preetham", input=files["dirs.csv"])["output"] == cli


def test_progress_reports_steps_and_an_exception_in_it_stops_the_operation(tmp_path):
    """progress(done, total, step) between steps; an exception it raises stops the operation
    there, propagates, and leaves no output."""
    calls = []
    out = tmp_path / "w.json"
    pyskylight.run("nn train", progress=lambda *a: calls.append(a), iterations=5, seed=1,
                   max_error=1000,
                   output=out)
    # Every iteration of every start, counted on: 1, 2, ... up to the total announced.
    assert [c[0] for c in calls] == list(range(1, len(calls) + 1)), calls
    assert len(calls) >= 5 and all(c[1] == len(calls) for c in calls), calls
    assert all(isinstance(c[2], str) for c in calls)
    out.unlink()

    def stop(done, total, step):
        if done == 2:
            raise ValueError("stop here")
    with pytest.raises(ValueError, match="stop here"):
        pyskylight.run("nn train", progress=stop, iterations=50, seed=1, max_error=1000,
                       output=out)
    assert list(tmp_path.iterdir()) == []
