"""Shared fixtures of the stickslip Python tests (run by ctest as python_stickslip).

Environment (set by tests/CMakeLists.txt): PYTHONPATH=<build>/python, STICKSLIP_CLI (the
stickslip-cli binary the module is compared against), STICKSLIP_SHARED_DIR (../shared).
"""
import csv
import io
import json
import os
import pathlib
import subprocess

import pytest

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parent.parent


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("STICKSLIP_CLI", str(SOURCE / "build" / "bin" / "stickslip-cli"))
    assert os.access(path, os.X_OK), f"stickslip-cli not found at {path} (set STICKSLIP_CLI)"
    return path


@pytest.fixture(scope="session")
def shared():
    path = pathlib.Path(os.environ.get("STICKSLIP_SHARED_DIR", str(SOURCE.parent / "shared")))
    assert (path / "data").is_dir(), f"shared data not found at {path} (set STICKSLIP_SHARED_DIR)"
    return path


@pytest.fixture(scope="session")
def damper(shared):
    return shared / "data" / "real" / "friction-damper"


def run_cli(cli, *args, check=True):
    """Runs stickslip-cli with args; returns its stdout as text."""
    r = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=300)
    if check:
        assert r.returncode == 0, f"stickslip-cli {' '.join(map(str, args))} failed ({r.returncode}): {r.stderr}"
    return r


def read_csv_text(text):
    """(header, rows as lists of str) of a CSV text with '#' comment lines."""
    lines = [l for l in text.splitlines() if l and not l.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    return rows[0], rows[1:]


def assert_columns_equal(header, rows, columns, int_columns=()):
    """The module's columns equal the CLI's CSV columns, to print precision."""
    assert list(columns.keys()) == header
    for j, name in enumerate(header):
        got = columns[name]
        assert len(got) == len(rows), name
        for i, row in enumerate(rows):
            v = got[i]
            text = str(int(v)) if name in int_columns else (v if isinstance(v, str) else "%.10g" % v)
            assert text == row[j], f"{name}[{i}]: module {text} vs CLI {row[j]}"


def strip_keys(obj, keys=("wall_time_s", "start_s", "wall_s", "program")):
    """A JSON value without the keys that differ between two runs (timing, the timeline's times, program name)."""
    if isinstance(obj, dict):
        return {k: strip_keys(v, keys) for k, v in obj.items() if k not in keys}
    if isinstance(obj, list):
        return [strip_keys(v, keys) for v in obj]
    return obj


def load_json(path):
    with open(path) as f:
        return json.load(f)
