"""skylight.report: the CLI's report from Python (quick), options from the schema."""

import json

import pytest

import skylight


def test_quick_report(tmp_path):
    files = skylight.report(tmp_path / "r", quick=True)
    assert "index.html" in files and "report.json" in files
    j = json.loads((tmp_path / "r" / "report.json").read_text())
    assert j["quick"] is True and "which_model_to_trust_where" in j
    with pytest.raises(skylight.InvalidArgument, match="quik is not a parameter of report; "
                                                       "did you mean 'quick'"):
        skylight.report(tmp_path / "r2", quik=True)
    with pytest.raises(OSError):
        skylight.report(tmp_path / "r3", quick=True, epw=str(tmp_path / "missing.epw"))
    assert not (tmp_path / "r3").exists()
