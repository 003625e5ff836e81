"""pyskylight.distributed on a LocalCluster of 2 worker processes (docs/SCALE.md): the sky matrices of
several weather files equal `daylight --epw` run one by one, bit for bit; a corrupt file is
reported with its name while the others finish; a worker killed mid-task is replaced and the run
ends with the same outputs; a rerun skips complete outputs; photos' turbidity equals `estimate`."""
import filecmp
import json
import os
import shutil

import pytest

import pyskylight as sk

distributed = pytest.importorskip("distributed")
from pyskylight import distributed as skd  # noqa: E402

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "data")
EPW = os.path.join(DATA, "weather", "synthetic_munich.epw")
# One week of records keeps a task at ~10 ms; the matrices are the same code as the year's.
HOURS = "4000-4168"


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as c:
        yield c


@pytest.fixture()
def sites(tmp_path):
    """Four weather files (copies of the sample year under other names) and one corrupt."""
    paths = []
    for k in range(4):
        p = tmp_path / f"site{k}.epw"
        shutil.copyfile(EPW, p)
        paths.append(str(p))
    bad = tmp_path / "broken.epw"
    text = open(EPW).read().splitlines()
    text[4100] = text[4100].replace(",", ";", 3)
    bad.write_text("\n".join(text) + "\n")
    return paths, str(bad)


def serial(epw, out):
    sk.run("daylight", epw=epw, output=out, hours=HOURS, patches="tregenza")
    return out


def test_matrices_equal_the_one_by_one_runs(client, sites, tmp_path):
    paths, _ = sites
    summary = skd.sky_matrices(paths, tmp_path / "out", hours=HOURS, client=client)
    assert [r["status"] for r in summary] == ["ok"] * 4
    assert [r["site"] for r in summary] == [f"site{k}" for k in range(4)]
    for r, p in zip(summary, paths):
        reference = serial(p, str(tmp_path / (r["site"] + "_serial.npy")))
        assert filecmp.cmp(r["output"], reference, shallow=False)
        assert r["hours"] > 50 and r["seconds"] > 0.0


def test_a_corrupt_file_fails_alone_and_writes_nothing(client, sites, tmp_path, caplog):
    paths, bad = sites
    out = tmp_path / "out"
    with caplog.at_level("WARNING", logger="pyskylight.distributed"):
        summary = skd.sky_matrices(paths[:2] + [bad], out, hours=HOURS, client=client)
    assert [r["status"] for r in summary] == ["ok", "ok", "failed"]
    assert "broken.epw" in summary[2]["error"] and "line 4101" in summary[2]["error"]
    assert sorted(os.listdir(out)) == ["site0.npy", "site1.npy"]  # no partial or temporary file
    assert sum("broken.epw" in m for m in caplog.messages) == 1


def test_a_rerun_skips_complete_outputs(client, sites, tmp_path):
    paths, _ = sites
    out = tmp_path / "out"
    skd.sky_matrices(paths[:2], out, hours=HOURS, client=client)
    before = {f: os.stat(out / f).st_mtime_ns for f in os.listdir(out)}
    again = skd.sky_matrices(paths[:2], out, hours=HOURS, client=client)
    assert [r["status"] for r in again] == ["skipped", "skipped"]
    assert {f: os.stat(out / f).st_mtime_ns for f in os.listdir(out)} == before


def _kill_once(item, marker_dir):
    """The first attempt at site1 kills its worker process (as an out-of-memory kill would)."""
    marker = os.path.join(marker_dir, "killed")
    if item[0].endswith("site1.epw") and not os.path.exists(marker):
        open(marker, "w").close()
        os._exit(1)


def test_a_killed_worker_is_replaced_and_the_outputs_are_the_same(client, sites, tmp_path):
    paths, _ = sites
    marker_dir = str(tmp_path)
    fault = lambda item: _kill_once(item, marker_dir)  # noqa: E731
    summary = skd.sky_matrices(paths, tmp_path / "out", hours=HOURS, client=client,
                               before_task=fault)
    assert os.path.exists(os.path.join(marker_dir, "killed"))
    assert [r["status"] for r in summary] == ["ok"] * 4
    for r, p in zip(summary, paths):
        assert filecmp.cmp(r["output"], serial(p, str(tmp_path / (r["site"] + "_s.npy"))),
                           shallow=False)
    assert sorted(f for f in os.listdir(tmp_path / "out")) == [f"site{k}.npy" for k in range(4)]


def test_same_names_are_refused_before_any_work(client, tmp_path):
    with pytest.raises(sk.InvalidArgument, match="would both write site.npy"):
        skd.sky_matrices(["a/site.epw", "b/site.epw"], tmp_path / "out", client=client)
    assert not (tmp_path / "out").exists()


def test_turbidity_of_photos_equals_estimate(client):
    photo = os.path.join(DATA, "hdr_sky", "city.exr")
    rows = skd.estimate_turbidity([photo, photo + ".missing"], projection="equirect",
                                  client=client)
    one = sk.run("estimate", image=photo, projection="equirect")
    assert rows[0]["status"] == "ok" and rows[0]["turbidity"] == one["turbidity"]
    assert rows[0]["sun_zenith_deg"] == one["sun_zenith_deg"]
    assert rows[1]["status"] == "failed" and "missing" in rows[1]["error"]


def test_measured_compare_equals_measured(client, tmp_path):
    rows = skd.measured_compare([None, str(tmp_path / "missing")], models=["preetham", "cie"],
                                client=client)
    assert [(r["model"], r["status"]) for r in rows] == [
        ("preetham", "ok"), ("cie", "ok"), ("preetham", "failed"), ("cie", "failed")]
    one = sk.run("measured", model="cie")
    assert rows[1]["median_luminance_rms_shape"] == one["median_luminance_rms_shape"]
    assert rows[1]["captures"] == len(one["captures"]) > 0
    assert "missing" in rows[2]["error"]


def test_train_networks_writes_each_network_or_reports_its_failure(client, tmp_path):
    configs = {"good": dict(source="preetham", iterations=100, starts=2, seed=1),
               "short": dict(source="preetham", iterations=20, starts=1, seed=1)}
    rows = skd.train_networks(configs, tmp_path / "nets", client=client)
    assert [r["status"] for r in rows] == ["ok", "failed"]
    assert "held-out check" in rows[1]["error"]
    assert sorted(os.listdir(tmp_path / "nets")) == ["good.json"]
    sk.run("nn train", output=str(tmp_path / "serial.json"), **configs["good"])

    def network(path):  # the file without its run's clock (provenance date, training time)
        j = json.loads(open(path).read())
        for key in ("date", "training_seconds"):
            j["provenance"].pop(key)
        return j
    assert network(tmp_path / "nets" / "good.json") == network(tmp_path / "serial.json")
