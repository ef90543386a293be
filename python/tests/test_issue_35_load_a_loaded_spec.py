"""ddirac.load takes a loaded Spec as it takes a path: its file, its own overrides, then the new ones on
top — equal to loading the file with both sets at once; so do the other functions that take a spec."""

import pathlib

import numpy as np
import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
SPEC = EXAMPLES / "double_spherical_pendulum.toml"
FIRST = {"method.reduced": False, "time.steps": 200, "time.duration": 2.0}
SECOND = {"method.rule": "trapezoid", "time.steps": 150}


def test_overrides_on_a_loaded_spec_are_applied_on_top_of_its_own():
    spec = ddirac.load(SPEC, overrides=FIRST)
    again = ddirac.load(spec, overrides=SECOND)
    both = ddirac.load(SPEC, overrides={**FIRST, **SECOND})
    assert isinstance(again, ddirac.Spec)
    assert (again.steps, again.step, again.method) == (both.steps, both.step, both.method)
    assert again.steps == 150 and again.method["rule"] == "trapezoid" and again.method["reduced"] is False
    np.testing.assert_array_equal(again.q0, both.q0)
    a, b = again.run(), both.run()
    np.testing.assert_array_equal(a.q, b.q)
    np.testing.assert_array_equal(a.p, b.p)
    # The spec loaded first is unchanged, and loading it without overrides gives it again.
    assert spec.steps == 200 and spec.method["rule"] == "midpoint"
    same = ddirac.load(spec)
    assert (same.steps, same.step, same.method) == (spec.steps, spec.step, spec.method)


def test_an_ensemble_of_a_spec_loaded_twice_is_that_of_both_overrides():
    members = {"initial.q.phi1": np.array([2.25, 2.3])}
    twice = ddirac.ensemble(ddirac.load(ddirac.load(SPEC, overrides=FIRST), overrides=SECOND), members=members,
                            threads=1)
    once = ddirac.ensemble(ddirac.load(SPEC, overrides={**FIRST, **SECOND}), members=members, threads=1)
    np.testing.assert_array_equal(twice.final_q, once.final_q)


def test_what_is_neither_a_path_nor_a_spec_is_refused_naming_both():
    with pytest.raises(ddirac.Error, match="path of a spec file or a ddirac.Spec"):
        ddirac.load(42)
