"""sweep() and map(): the columns of `stickslip-cli sweep --out/--summary` and `map --out`."""
import pytest

import stickslip
from conftest import assert_columns_equal, read_csv_text, run_cli


def test_sweep_equals_cli(cli, tmp_path):
    r = stickslip.sweep("fig20", param="A", start="0.2mm", stop=0.6e-3, steps=3, direction="both", settle=3,
                        samples=4)
    run_cli(cli, "sweep", "--preset", "fig20", "--param", "A", "--from", "0.2mm", "--to", "0.6e-3", "--steps", "3",
            "--direction", "both", "--settle", "3", "--samples", "4", "--out", tmp_path / "s.csv",
            "--summary", tmp_path / "sum.csv")
    header, rows = read_csv_text((tmp_path / "s.csv").read_text())
    assert len(rows) == 6 * 4
    assert_columns_equal(header, rows, r["samples"], int_columns=("sample",))
    header, rows = read_csv_text((tmp_path / "sum.csv").read_text())
    assert_columns_equal(header, rows, r["summary"], int_columns=("period",))
    assert r["steps_per_period"] > 0


def test_sweep_with_tolerance_equals_cli(cli, tmp_path):
    r = stickslip.sweep("fig20", param="A", start="0.5mm", stop="1mm", steps=2, settle=5, samples=4,
                        lyapunov=False, tolerance=1e-4)
    run_cli(cli, "sweep", "--preset", "fig20", "--param", "A", "--from", "0.5mm", "--to", "1mm", "--steps", "2",
            "--settle", "5", "--samples", "4", "--no-lyapunov", "--tolerance", "1e-4", "--out", tmp_path / "s.csv",
            "--summary", tmp_path / "sum.csv")
    header, rows = read_csv_text((tmp_path / "s.csv").read_text())
    assert_columns_equal(header, rows, r["samples"], int_columns=("sample",))
    with pytest.raises(ValueError, match="tolerance"):
        stickslip.sweep("fig20", start="0.5mm", stop="1mm", steps=2, tolerance=1e-4)  # Lyapunov needs the fixed step


def test_map_equals_cli(cli, tmp_path):
    r = stickslip.map("fig20", param="A", start=0.3e-3, stop=0.6e-3, steps=2, param2="f", start2=3, stop2=4,
                      steps2=2, settle=3, samples=4, threads=2)
    run_cli(cli, "map", "--preset", "fig20", "--param", "A", "--from", "0.3e-3", "--to", "0.6e-3", "--steps", "2",
            "--param2", "f", "--from2", "3", "--to2", "4", "--steps2", "2", "--settle", "3", "--samples", "4",
            "--out", tmp_path / "m.csv")
    header, rows = read_csv_text((tmp_path / "m.csv").read_text())
    assert len(rows) == 4
    assert_columns_equal(header, rows, r, int_columns=("period",))


def test_sweep_and_map_bad_arguments():
    with pytest.raises(ValueError, match="is not a parameter key"):
        stickslip.sweep(param="nope", start=1, stop=2, steps=2)
    with pytest.raises(ValueError, match="start is required"):
        stickslip.sweep(stop=1e-3)
    with pytest.raises(ValueError, match="direction 'sideways'"):
        stickslip.sweep(start=1e-4, stop=2e-4, direction="sideways")
    with pytest.raises(ValueError, match="steps"):
        stickslip.map(start=1e-4, stop=2e-4, steps=0, start2=3, stop2=4)
    with pytest.raises(ValueError, match="unknown keyword"):
        stickslip.map(start=1e-4, stop=2e-4, start2=3, stop2=4, colour="red")
