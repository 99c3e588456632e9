"""simulate(), params(), presets(): the same numbers as `stickslip-cli simulate` and `presets`."""
import numpy as np
import pytest

import stickslip
from conftest import assert_columns_equal, read_csv_text, run_cli


def test_simulate_equals_cli_csv(cli):
    cols = stickslip.simulate("fig20", cycles=5, A=0.4e-3)
    assert list(cols) == stickslip.RUN_COLUMNS
    assert all(isinstance(v, np.ndarray) and v.dtype == np.float64 for v in cols.values())
    out = run_cli(cli, "simulate", "--preset", "fig20", "--cycles", "5", "--set", "A=0.4e-3", "--out", "-").stdout
    header, rows = read_csv_text(out)
    assert len(rows) > 1000
    assert_columns_equal(header, rows, cols, int_columns=("stuck",))


def test_units_model_setup_and_flags_equal_cli(cli):
    kw = dict(model="coulomb", mu=0.3, tN="7N", A="0.8mm", cycles=2, dt="20us", output_every=1e-3)
    cols = stickslip.simulate("default", **kw)
    out = run_cli(cli, "simulate", "--model", "coulomb", "--set", "mu=0.3", "--set", "tN=7N", "--set", "A=0.8mm",
                  "--cycles", "2", "--dt", "20us", "--output-every", "1e-3", "--out", "-").stdout
    header, rows = read_csv_text(out)
    assert_columns_equal(header, rows, cols, int_columns=("stuck",))


def test_prescribed_input_equals_cli(cli, tmp_path):
    t = np.linspace(0, 1, 401)
    path = tmp_path / "slip.csv"
    np.savetxt(path, np.column_stack([t, 1e-3 * np.sin(2 * np.pi * 2 * t)]), delimiter=",",
               header="time_s,rel_disp_m", comments="")
    cols = stickslip.simulate(input=str(path), cycles=1)
    out = run_cli(cli, "simulate", "--input", path, "--cycles", "1", "--out", "-").stdout
    header, rows = read_csv_text(out)
    assert_columns_equal(header, rows, cols, int_columns=("stuck",))


def test_bad_arguments_raise_value_error_naming_field_value_range():
    with pytest.raises(ValueError, match=r"tN = -1 is out of range: must be > 0"):
        stickslip.simulate(tN=-1)
    with pytest.raises(ValueError, match=r"unknown keyword argument\(s\) 'bogus'"):
        stickslip.simulate(bogus=1)
    with pytest.raises(ValueError, match=r"unknown preset 'fig99'"):
        stickslip.simulate("fig99")
    with pytest.raises(ValueError, match=r"rate-state, coulomb"):
        stickslip.simulate(model="stribeck")
    with pytest.raises(ValueError, match=r"needs setup='prescribed'"):
        stickslip.simulate(input="x.csv", setup="dynamics")
    with pytest.raises(OSError):
        stickslip.simulate(input="/no/such/file.csv")
    with pytest.raises(TypeError):
        stickslip.simulate(A=[1, 2])


def test_params_and_presets():
    p = stickslip.params("fig20", A="0.4mm", model="coulomb", mu=0.3)
    assert p["A"] == pytest.approx(0.4e-3) and p["model"] == "coulomb" and p["mu"] == 0.3
    presets = stickslip.presets()
    names = [x["name"] for x in presets]
    assert names[0] == "default" and "fig20" in names
    fig20 = presets[names.index("fig20")]
    assert fig20["description"] and set(stickslip.PARAM_KEYS) <= set(fig20["params"])
    assert fig20["params"] == stickslip.params("fig20")
