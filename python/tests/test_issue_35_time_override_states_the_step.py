"""Overriding one key of ``[time]`` silently changed the step: ``time.duration=100000`` on the main
example keeps ``steps = 10⁴``, so h = 10, and the run died with a message that did not state h. Loading
now warns with the h that results, and a failed step states h (``ConvergenceError.h``)."""

from pathlib import Path

import pytest

import ddirac

MAIN = Path(__file__).resolve().parents[2] / "examples" / "double_spherical_pendulum.toml"


def test_an_override_that_changes_the_step_warns_and_the_failure_states_it():
    steps, duration = 10_000, 100_000.0
    h = duration / steps
    with pytest.warns(UserWarning, match=rf"the step h = {h:g} .*the spec's own step is h = 0\.01"):
        spec = ddirac.load(MAIN, overrides={"time.duration": duration})
    assert spec.step == h and spec.steps == steps
    with pytest.raises(ddirac.ConvergenceError) as failure:
        spec.run()
    assert failure.value.h == h
    assert f"h = {h:g})" in str(failure.value)


def test_an_override_that_keeps_the_step_is_silent(recwarn):
    spec = ddirac.load(MAIN, overrides={"time.duration": 1.0, "time.steps": 100})
    assert spec.step == pytest.approx(0.01, rel=1e-15)
    assert not [w for w in recwarn if "ddirac.load" in str(w.message)]
