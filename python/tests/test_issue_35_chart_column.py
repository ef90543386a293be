"""Run.columns() has the `chart` column that trajectory.csv has for a run that can switch charts of an
atlas (examples/spherical_pendulum.toml), with the same values, and none where trajectory.csv has none."""

import csv
import pathlib
import subprocess

import numpy as np
import pytest

import ddirac
import command_line

REPO = pathlib.Path(__file__).resolve().parents[2]
SPEC = REPO / "examples" / "spherical_pendulum.toml"
# Close to the pole: the run enters the caps' charts.
OVERRIDES = {"time.duration": 4.0, "initial.v.phi": 0.2}


def cli_trajectory(tmp_path, overrides):
    out = tmp_path / "cli"
    args = [command_line.built(), "run", str(SPEC), "--out", str(out), "--quiet"]
    for key, value in overrides.items():
        args += ["--set", f"{key}={str(value).lower() if isinstance(value, bool) else value}"]
    done = subprocess.run(args, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) if x else np.nan for x in row] for row in rows[1:]])


def test_an_atlas_run_has_the_chart_column_of_trajectory_csv(tmp_path):
    header, values = cli_trajectory(tmp_path, OVERRIDES)
    assert "chart" in header
    run = ddirac.load(SPEC, overrides=OVERRIDES).run()
    columns = run.columns()
    assert list(columns) == header
    chart = values[:, header.index("chart")]
    assert np.any(chart > 0), "the run should enter another chart"
    np.testing.assert_array_equal(columns["chart"], chart)
    np.testing.assert_array_equal(run.chart, chart)
    if _has("pandas"):
        assert list(run.to_pandas().columns) == header
    # Read back from the files the run writes, the column is there too.
    written = ddirac.load(SPEC, overrides=OVERRIDES).run(out=tmp_path / "py")
    np.testing.assert_array_equal(written.columns()["chart"], chart)


def test_without_switching_there_is_no_chart_column(tmp_path):
    overrides = {**OVERRIDES, "method.atlas": False}
    header, _ = cli_trajectory(tmp_path, overrides)
    assert "chart" not in header
    run = ddirac.load(SPEC, overrides=overrides).run()
    assert list(run.columns()) == header and run.chart is None
    # A system without an atlas.
    pendulum = ddirac.System(lagrangian="0.5*phi_dot^2 + cos(phi)", shape=["phi"], angles=["phi"])
    plain = ddirac.simulate(pendulum, q0=[1.0], p0=[0.0], step=0.01, steps=10)
    assert "chart" not in plain.columns() and plain.chart is None


def _has(module):
    try:
        __import__(module)
    except ImportError:
        return False
    return True
