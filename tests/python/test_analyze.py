"""analyze(): the JSON report of `stickslip-cli analyze`, as a dict."""
import json

import pytest

import stickslip
from conftest import run_cli, strip_keys


def test_analyze_equals_cli_on_simulated_run(cli, tmp_path):
    path = tmp_path / "run.csv"
    run_cli(cli, "simulate", "--preset", "fig20", "--cycles", "8", "--out", path)
    got = stickslip.analyze(str(path))
    want = json.loads(run_cli(cli, "analyze", "--input", path).stdout)
    assert got["program"].startswith("stickslip ")
    assert strip_keys(got) == strip_keys(want)
    assert got["forcing_frequency_source"] == "file"


def test_analyze_equals_cli_on_measured_run(cli, damper):
    path = damper / "1Hz_30lb_1in.csv"
    got = stickslip.analyze(path, frequency=1.0, max_lag=1.5)
    want = json.loads(run_cli(cli, "analyze", "--input", path, "--frequency", "1", "--max-lag", "1.5").stdout)
    assert strip_keys(got) == strip_keys(want)


def test_analyze_a_dict_of_columns():
    run = stickslip.simulate("fig20", cycles=8)
    got = stickslip.analyze(run, frequency=3.0)
    assert got["input"] == "<dict>" and got["rows"] == len(run["time_s"])
    assert got["forcing_frequency_source"] == "option"
    assert "loops" in got and "spectrum" in got


def test_analyze_errors():
    with pytest.raises(ValueError, match="need at least 64"):
        stickslip.analyze({"time_s": [0.0, 1.0]})
    with pytest.raises(OSError):
        stickslip.analyze("/no/such/run.csv")
