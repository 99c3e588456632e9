"""fit() and identify(): the same report as `stickslip-cli fit/identify --report`, as a dict."""
import pytest

import stickslip
from conftest import load_json, run_cli, strip_keys


def test_fit_equals_cli_report(cli, damper, tmp_path):
    data = [str(damper / "1Hz_30lb_1in.csv")]
    val = [str(damper / "1Hz_36lb_1in.csv")]
    got = stickslip.fit(data, validate_on=val, model="both", free="mu,epsT", multistarts=1, max_iterations=15)
    run_cli(cli, "fit", "--data", *data, "--validate-on", *val, "--model", "both", "--free", "mu,epsT",
            "--multistarts", "1", "--max-iterations", "15", "--report", tmp_path / "fit.json")
    want = load_json(tmp_path / "fit.json")
    assert strip_keys(got) == strip_keys(want)
    assert got["validation"] == "by run (--validate-on)"


def test_identify_equals_cli_report(cli, damper, tmp_path):
    data = [str(damper / n) for n in ("1Hz_30lb_1in.csv", "1Hz_36lb_1in.csv", "0.5Hz_30lb_1in.csv")]
    opts = dict(setup="prescribed", candidates=["normal_load_mu"], max_effects=1, null_replicas=20, multistarts=1)
    got = stickslip.identify(data, **opts)
    run_cli(cli, "identify", "--data", *data, "--setup", "prescribed", "--candidates", "normal_load_mu",
            "--max-effects", "1", "--null-replicas", "20", "--multistarts", "1", "--quiet",
            "--report", tmp_path / "id.json")
    want = load_json(tmp_path / "id.json")
    assert got["ok"] is True
    assert strip_keys(got) == strip_keys(want)
    assert got["selection"]["jacobian"] == "forward"
    # Prescribed runs used every `decimation`-th sample: the law is driven through the recorded slip.
    sel = got["selection"]
    assert sel["state_step"] == "constant_rate"
    assert sel["law_input"] == ("recorded_slip" if sel["decimation"] > 1 else "linear")


def test_identify_central_jacobian_equals_cli_report(cli, damper, tmp_path):
    data = [str(damper / n) for n in ("1Hz_30lb_1in.csv", "1Hz_36lb_1in.csv", "0.5Hz_30lb_1in.csv")]
    got = stickslip.identify(data, setup="prescribed", candidates=["normal_load_mu"], max_effects=1, null_replicas=20,
                             multistarts=1, forward_jacobian=False)
    run_cli(cli, "identify", "--data", *data, "--setup", "prescribed", "--candidates", "normal_load_mu",
            "--max-effects", "1", "--null-replicas", "20", "--multistarts", "1", "--central-jacobian", "--quiet",
            "--report", tmp_path / "id.json")
    want = load_json(tmp_path / "id.json")
    assert got["ok"] is True and got["selection"]["jacobian"] == "central"
    assert got["selection"]["coordinates"] == "steady_state_curve"  # both set-ups (session 29)
    assert strip_keys(got) == strip_keys(want)


def test_fit_identify_bad_arguments(damper):
    run = str(damper / "1Hz_30lb_1in.csv")
    with pytest.raises(ValueError, match="--model stribeck"):
        stickslip.fit(run, model="stribeck")
    with pytest.raises(ValueError, match="unknown keyword argument 'colour'"):
        stickslip.fit(run, colour="red")
    with pytest.raises(ValueError, match="not in the catalogue"):
        stickslip.identify(run, candidates="no_such_effect")
    with pytest.raises(OSError):
        stickslip.fit("/no/such/run.csv")


def test_identify_self_test_equals_cli_report(cli, damper, tmp_path):
    data = [str(damper / n) for n in ("1Hz_30lb_1in.csv", "1Hz_36lb_1in.csv")]
    got = stickslip.identify(data, setup="prescribed", candidates=["normal_load_mu", "backlash"], max_effects=0,
                             multistarts=1, self_test=True, self_test_replicas=4, self_test_levels=[0.5, 1.0],
                             self_test_size={"backlash": 1e-3})
    run_cli(cli, "identify", "--data", *data, "--setup", "prescribed", "--candidates", "normal_load_mu,backlash",
            "--max-effects", "0", "--multistarts", "1", "--self-test", "--self-test-replicas", "4",
            "--self-test-levels", "0.5,1", "--self-test-size", "backlash=1e-3", "--quiet", "--report", tmp_path / "st.json")
    want = load_json(tmp_path / "st.json")
    assert strip_keys(got) == strip_keys(want)
    rows = got["self_test"]["rows"]
    assert rows[-1]["effect"] == "backlash" and rows[-1]["size"] == 1e-3 and rows[-1]["replicas"] == 4
    with pytest.raises(ValueError, match="self-test-size 'backlash'"):
        stickslip.identify(data, setup="prescribed", self_test=True, self_test_size=["backlash"])
    with pytest.raises(ValueError, match="is the size parameter: state it as backlash=VALUE"):
        stickslip.identify(data, setup="prescribed", self_test=True, self_test_size={"backlash.halfWidth_m": 1e-3})
