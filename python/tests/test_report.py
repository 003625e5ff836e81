"""pyskylight.report: the CLI's report from Python (quick), options from the schema."""

import json

import pytest

import pyskylight


def test_quick_report(tmp_path):
    record = pyskylight.report(tmp_path / "r", quick=True)
    assert record["index"] == str(tmp_path / "r" / "index.html") and record["files"] > 10
    j = json.loads((tmp_path / "r" / "report.json").read_text())
    assert j["quick"] is True and "which_model_to_trust_where" in j
    with pytest.raises(pyskylight.InvalidArgument, match="quik is not a parameter of report; "
                                                       "did you mean 'quick'"):
        pyskylight.report(tmp_path / "r2", quik=True)
    with pytest.raises(pyskylight.InvalidArgument, match="missing.epw': no such file"):
        pyskylight.report(tmp_path / "r3", quick=True, epw=str(tmp_path / "missing.epw"))
    assert not (tmp_path / "r3").exists()
