"""ddirac.load: spec files as `ddirac run` reads them, with overrides as `--set` gives them."""

import json
import os
import pathlib

import numpy as np
import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
DSP = EXAMPLES / "double_spherical_pendulum.toml"


def test_a_loaded_spec_runs_as_simulate_does_with_its_values():
    spec = ddirac.load(DSP, overrides={"time.steps": 500, "time.duration": 5.0})
    assert spec.system.name == "double_spherical_pendulum" and spec.steps == 500 and spec.step == 0.01
    assert spec.method["reduced"] is True and spec.method["rule"] == "midpoint"
    from_spec = spec.run()
    direct = ddirac.simulate(spec.system, q0=spec.q0, p0=spec.p0, step=0.01, steps=500, reduced=True, every=10)
    assert np.array_equal(from_spec.q, direct.q) and np.array_equal(from_spec.p, direct.p)


def test_overrides_of_every_kind_reach_the_spec():
    spec = ddirac.load(DSP, overrides={
        "method.reduced": False,                      # bool
        "time.steps": 200, "time.duration": 2.0,      # int, float
        "method.derivatives": "dual",                 # string
        "initial.q": {"vartheta1": 0.5, "phi1": 2.25, "vartheta2": 2.0, "phi2": 3.0},  # table
        "initial.p": [0.0, 0.0, 1.0, 1.0],            # array
    })
    assert spec.method["reduced"] is False and spec.method["derivatives"] == "dual"
    assert spec.steps == 200 and list(spec.q0) == [0.5, 2.25, 2.0, 3.0]


def test_a_run_into_a_directory_writes_the_files_and_reads_back_the_same_arrays(tmp_path):
    spec = ddirac.load(EXAMPLES / "charged_particle.toml")
    written = spec.run(out=tmp_path / "cp")
    in_memory = spec.run()
    names = sorted(os.listdir(tmp_path / "cp"))
    assert {"trajectory.csv", "summary.json", "exact.csv"} <= set(names)
    assert np.array_equal(written.q, in_memory.q) and np.array_equal(written.p, in_memory.p)
    assert np.array_equal(written.energy, in_memory.energy)
    with open(tmp_path / "cp" / "summary.json") as f:
        summary = json.load(f)
    assert written.summary == summary and summary["final"]["q"] == list(in_memory.q[-1])
    # The summary of a run without files is the dict of summary.json but for what only a file run has.
    timing = {"wall_seconds", "total_wall_seconds", "spec"}
    assert set(summary) - set(in_memory.summary) == {"spec", "total_wall_seconds"}
    assert {k: v for k, v in in_memory.summary.items() if k not in timing} == \
        {k: v for k, v in summary.items() if k not in timing}


def test_spec_errors_carry_the_command_lines_diagnostic():
    with pytest.raises(ddirac.Error) as error:
        ddirac.load(DSP, overrides={"method.rule": "simpson"})
    text = str(error.value)
    assert "unknown rule `simpson`" in text and 'rule = "simpson"' in text and "midpoint" in text
    with pytest.raises(ddirac.Error, match="no-such.toml"):
        ddirac.load(EXAMPLES / "no-such.toml")
    with pytest.raises(ddirac.Error, match="not a spec value"):
        ddirac.load(DSP, overrides={"time.steps": object()})
