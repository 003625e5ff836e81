"""pyskylight.nn: a small sky network trained from Python is the CLI's (same seed, same weights
file), usable as the nn model; bad options name themselves; Ctrl-C (a signal) stops training."""

import json
import os
import signal
import subprocess

import numpy as np
import pytest

import pyskylight

CLI = os.environ.get("SKYLIGHT_CLI", "skylight")

# A small protocol (seconds, not the paper's minutes); the held-out bound is lifted because so
# small a network is not the point here.
SMALL = dict(suns=3, view_zeniths=3, view_azimuths=4, iterations=15, starts=1, hidden=6,
             max_error=1e5)


def cli_flags(options):
    out = []
    for k, v in options.items():
        out += [f"--{k.replace('_', '-')}", str(v)]
    return out


def test_training_matches_the_cli_and_loads_as_a_sky(tmp_path):
    py_out = tmp_path / "py.json"
    summary = pyskylight.nn.train(py_out, source="preetham", seed=3, **SMALL)
    assert summary["iterations"] <= 15 and summary["source"] == "preetham"
    cli_out = tmp_path / "cli.json"
    subprocess.run([CLI, "nn", "train", "--source", "preetham", "--seed", "3", *cli_flags(SMALL),
                    "-o", str(cli_out)], check=True, capture_output=True)
    a, b = json.loads(py_out.read_text()), json.loads(cli_out.read_text())
    # The same training (deterministic for a seed): identical weights.
    assert a["parameters"] == b["parameters"] and a["architecture"] == b["architecture"]
    sky = pyskylight.nn.load(py_out, turbidity=3, sun_zenith=40)
    assert sky.model == "nn"
    assert np.all(sky.evaluate([0, 30], [0, 90], quantity="luminance") > 0)


def test_bad_options_and_interrupt(tmp_path):
    with pytest.raises(pyskylight.InvalidArgument, match="iteratons is not a parameter of nn train; "
                                                         "did you mean 'iterations'"):
        pyskylight.nn.train(tmp_path / "x.json", iteratons=3)
    calls = []

    def interrupt(done, total, step):
        calls.append(done)
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        pyskylight.nn.train(tmp_path / "y.json", progress=interrupt,
                          **dict(SMALL, iterations=2000, time_limit=600))
    assert len(calls) <= 5  # stopped between iterations
    assert not (tmp_path / "y.json").exists()


def test_glsl_is_the_clis_export(tmp_path):
    out = tmp_path / "sky.glsl"
    subprocess.run([CLI, "nn", "export", "--glsl", str(out)], check=True, capture_output=True)
    assert pyskylight.nn.glsl() == out.read_text()
    assert "#version 330 core" in pyskylight.nn.glsl()
    with pytest.raises(pyskylight.InvalidArgument, match="missing.json': no such file"):
        pyskylight.nn.glsl(tmp_path / "missing.json")


def test_images_train_a_network_as_the_cli(tmp_path):
    # Three rendered captures (hosek, the sun given in the list), as `nn train --images` reads
    # them; the middle one is the held-out capture.
    suns = [(30, 120), (45, 150), (60, 180)]
    lines = ["file,sun_zenith_deg,sun_azimuth_deg"]
    for k, (z, a) in enumerate(suns):
        sky = pyskylight.Sky("hosek", turbidity=3, sun_zenith=z, sun_azimuth=a)
        pyskylight.io.write(tmp_path / f"c{k}.exr", sky.render(96, 48))
        lines.append(f"c{k}.exr,{z},{a}")
    (tmp_path / "seq.csv").write_text("\n".join(lines) + "\n")
    opts = dict(hidden=8, iterations=30, samples=300, max_error=1000, seed=2)
    r = pyskylight.nn.train(tmp_path / "w.json", images=tmp_path / "seq.csv", **opts)
    assert [i["line"] for i in r["images"]] == [2, 3, 4]
    assert [i["sun_from"] for i in r["images"]] == ["list"] * 3
    assert r["images"][1]["sun_zenith_deg"] == pytest.approx(45.0)
    assert r["examples"] == 900 and "lines 3" in r["held_out_check"]
    cli = subprocess.run([CLI, "nn", "train", "--images", str(tmp_path / "seq.csv"),
                          "--hidden", "8", "--iterations", "30", "--samples", "300",
                          "--max-error", "1000", "--seed", "2", "-o", str(tmp_path / "c.json"),
                          "--json"], check=True, capture_output=True, text=True).stdout
    # The same record as the command line's (but the training's time).
    cli_record = json.loads(cli)
    for key in ("examples", "images", "iterations", "final_rmse", "held_out_check"):
        assert cli_record[key] == r[key], key
    mine = json.loads((tmp_path / "w.json").read_text())
    theirs = json.loads((tmp_path / "c.json").read_text())
    assert mine["parameters"] == theirs["parameters"]  # the same training, bit for bit
    with pytest.raises(pyskylight.InvalidArgument, match="images and source exclude each other"):
        pyskylight.nn.train(tmp_path / "x.json", source="hosek", images=tmp_path / "seq.csv")


def test_pietras_network_trains_and_warns_of_unread_options(tmp_path):
    with pytest.warns(pyskylight.SkylightWarning, match="starts is not read by this training"):
        r = pyskylight.nn.train(tmp_path / "p.json", source="nishita", network="pietras",
                              samples=2000, iterations=3, max_error=1e6, starts=3)
    assert r["network"] == "pietras" and r["weights"] > 0 and r["samples"] == 2000
    sky = pyskylight.Sky("pietras", weights=str(tmp_path / "p.json"), sun_zenith=40)
    assert np.isfinite(sky.evaluate([0, 60], [0, 90], quantity="xyz")).all()
