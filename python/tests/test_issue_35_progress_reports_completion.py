"""A progress callback hears of completion: its last call is progress(steps, steps) for a run
(ddirac.simulate, Spec.run) and progress(members, members) for an ensemble, however short the run; a
run that fails does not report completion."""

import pathlib

import numpy as np
import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
DSP = dict(q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01)


def test_simulate_reports_the_last_step():
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    for steps in (7, 3000):
        calls = []
        ddirac.simulate(dsp, steps=steps, progress=lambda k, n: calls.append((k, n)), **DSP)
        assert calls and calls[-1] == (steps, steps), calls[-3:]
        assert all(n == steps for _, n in calls) and [k for k, _ in calls] == sorted(k for k, _ in calls)
        assert [k for k, _ in calls].count(steps) == 1


def test_spec_run_and_ensemble_report_completion():
    spec = ddirac.load(EXAMPLES / "double_spherical_pendulum.toml", overrides={"time.steps": 50, "time.duration": 0.5})
    calls = []
    spec.run(progress=lambda k, n: calls.append((k, n)))
    assert calls[-1] == (50, 50)
    calls = []
    ddirac.ensemble(spec, members={"initial.q.phi1": np.array([2.25, 2.3, 2.35])}, threads=1,
                    progress=lambda k, n: calls.append((k, n)))
    assert calls[-1] == (3, 3)


def test_a_failed_run_does_not_report_completion():
    system = ddirac.System(lagrangian="0.5*x_dot^2 + 1/x", shape=["x"])
    calls = []
    with pytest.raises(ddirac.Error):
        # Falls into the singularity at x = 0 and fails there.
        ddirac.simulate(system, q0=[1.0], p0=[0.0], step=0.1, steps=100, on_energy_jump="error",
                        progress=lambda k, n: calls.append((k, n)))
    assert (100, 100) not in calls
