"""skylight.nn: a small sky network trained from Python is the CLI's (same seed, same weights
file), usable as the nn model; bad options name themselves; Ctrl-C (a signal) stops training."""

import json
import os
import signal
import subprocess

import numpy as np
import pytest

import skylight

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
    summary = skylight.nn.train(py_out, source="preetham", seed=3, **SMALL)
    assert summary["iterations"] <= 15 and summary["source"] == "preetham"
    cli_out = tmp_path / "cli.json"
    subprocess.run([CLI, "nn", "train", "--source", "preetham", "--seed", "3", *cli_flags(SMALL),
                    "-o", str(cli_out)], check=True, capture_output=True)
    a, b = json.loads(py_out.read_text()), json.loads(cli_out.read_text())
    # The same training (deterministic for a seed): identical weights.
    assert a["parameters"] == b["parameters"] and a["architecture"] == b["architecture"]
    sky = skylight.nn.load(py_out, turbidity=3, sun_zenith=40)
    assert sky.model == "nn"
    assert np.all(sky.evaluate([0, 30], [0, 90], quantity="luminance") > 0)


def test_bad_options_and_interrupt(tmp_path):
    with pytest.raises(skylight.InvalidArgument, match="iteratons is not a parameter of nn.train; "
                                                       "did you mean 'iterations'"):
        skylight.nn.train(tmp_path / "x.json", iteratons=3)
    calls = []

    def interrupt(iteration, mse):
        calls.append(iteration)
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        skylight.nn.train(tmp_path / "y.json", progress=interrupt,
                          **dict(SMALL, iterations=2000, time_limit=600))
    assert len(calls) <= 5  # stopped between iterations
    assert not (tmp_path / "y.json").exists()


def test_glsl_is_the_clis_export(tmp_path):
    out = tmp_path / "sky.glsl"
    subprocess.run([CLI, "nn", "export", "--glsl", str(out)], check=True, capture_output=True)
    assert skylight.nn.glsl() == out.read_text()
    assert "#version 330 core" in skylight.nn.glsl()
    with pytest.raises(OSError, match="cannot read"):
        skylight.nn.glsl(tmp_path / "missing.json")
