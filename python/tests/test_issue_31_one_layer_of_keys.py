"""One layer of keys: a method key, the time grid and the initial data mean the same, and are refused
with the same words, whether a spec file gives them (`ddirac.load`, as `ddirac run` reads it) or the
arguments of `ddirac.simulate` do."""

import pathlib

import numpy as np
import pytest

import ddirac
from ddirac import _ddirac

KEPLER = pathlib.Path(__file__).resolve().parents[2] / "examples" / "kepler.toml"
# The example's orbit over 1.0 time units: 500 steps of 0.002, reduced, midpoint.
SHORT = {"time.duration": 1.0}
Q0, P0 = {"r": 1.0, "phi": 0.0}, {"r": 0.0, "phi": 0.8}

# A value other than the default for every method key, each a valid run of the reduced Kepler problem.
VALUES = {
    "rule": "trapezoid",
    "variant": "minus",
    "reduced": False,
    "connection": [[0.3]],
    "tolerance": 1e-10,
    "max_iterations": 20,
    "jacobian": "fresh",
    "derivatives": "dual",
    "check_invariance": False,
    "on_energy_jump": "ignore",
    "energy_jump_threshold": 0.01,
    "order": 4,
    "composition": "triple-jump",
    "atlas": False,
    "sensitivities": True,
}


def direct(**keys):
    args = {"rule": "midpoint", "reduced": True, **keys}
    return ddirac.simulate(ddirac.System.builtin("kepler"), q0=Q0, p0=P0, step=0.002, duration=1.0, every=5, **args)


def from_spec(**keys):
    overrides = {**SHORT, **{f"method.{k}": v for k, v in keys.items()}}
    return ddirac.load(KEPLER, overrides=overrides).run()


def test_the_method_keys_are_the_spec_s_and_each_means_the_same_from_either_front_end():
    assert _ddirac.method_keys() == list(VALUES)
    for key, value in VALUES.items():
        extra = {"order": 4} if key == "composition" else {}
        a, b = direct(**{key: value}, **extra), from_spec(**{key: value}, **extra)
        assert np.array_equal(a.q, b.q) and np.array_equal(a.p, b.p), key
    # summary.json records every key, as the spec writes it, so that the run can be given again.
    recorded = from_spec(jacobian="fresh").summary["method"]
    assert set(VALUES) <= set(recorded) and recorded["jacobian"] == "fresh"
    assert direct(reuse_jacobian=True).summary["method"]["jacobian"] == "reuse"
    # A non-default value changes the run (so that the comparison above can fail).
    assert not np.array_equal(direct(rule="trapezoid", order=4).q, direct().q)


def test_reuse_jacobian_is_the_boolean_spelling_of_jacobian():
    assert np.array_equal(direct(reuse_jacobian=False).q, from_spec(jacobian="fresh").q)
    assert np.array_equal(direct(reuse_jacobian=True).q, direct(jacobian="reuse").q)
    with pytest.raises(ddirac.Error, match="give `jacobian` or `reuse_jacobian`, not both"):
        direct(jacobian="fresh", reuse_jacobian=False)


def test_a_loaded_spec_s_method_runs_again_as_the_same_method():
    spec = ddirac.load(KEPLER, overrides={**SHORT, "method.jacobian": "fresh", "method.order": 6})
    assert spec.method["jacobian"] == "fresh" and spec.method["composition"] == "kahan-li"
    method = dict(spec.method)
    run = ddirac.simulate(spec.system, q0=spec.q0, p0=spec.p0, step=spec.step, steps=spec.steps, every=5, **method)
    assert np.array_equal(run.q, spec.run().q)


# A wrong value of each kind, and the words both front ends refuse it with.
REFUSALS = [
    ({"rule": "simpson"}, "unknown rule `simpson`"),
    ({"tolerance": -1.0}, "tolerance` must be positive"),
    ({"tolerance": float("nan")}, "tolerance` is not finite (NaN)"),
    ({"max_iterations": 0}, "max_iterations` must be at least 1"),
    ({"order": 3}, "there is no method of order 3"),
    ({"jacobian": "sometimes"}, "unknown Jacobian policy `sometimes`"),
    ({"composition": "kahan-li"}, "the composition `kahan-li` has several orders"),
    ({"connection": [[1.0, 2.0]]}, "connection` has 2 entries, expected 1"),
    ({"derivatives": "symbolic"}, "unknown derivative evaluation `symbolic`"),
    ({"energy_jump_threshold": 0.0}, "energy_jump_threshold` must be positive"),
]


@pytest.mark.parametrize("keys, words", REFUSALS, ids=[next(iter(k)) for k, _ in REFUSALS])
def test_a_wrong_method_key_is_refused_in_the_same_words(keys, words):
    with pytest.raises(ddirac.Error) as argument:
        direct(**keys)
    with pytest.raises(ddirac.Error) as spec:
        from_spec(**keys)
    assert words in str(argument.value) and words in str(spec.value)


def test_a_wrong_grid_or_initial_vector_is_refused_in_the_same_words(tmp_path):
    system = ddirac.System.builtin("kepler")
    with pytest.raises(ddirac.Error) as argument:
        ddirac.simulate(system, q0=Q0, p0=P0, step=0.3, duration=1.0)
    with pytest.raises(ddirac.Error) as spec:
        ddirac.load(KEPLER, overrides={"time.step": 0.3, "time.duration": 1.0})
    assert "= 3.3333333333333335 is not a whole number of steps" in str(argument.value)
    assert "= 3.3333333333333335 is not a whole number of steps" in str(spec.value)

    with pytest.raises(ddirac.Error) as argument:
        ddirac.simulate(system, q0=[1.0, 0.0, 3.0], p0=P0, step=0.002, steps=5)
    with pytest.raises(ddirac.Error) as spec:
        wrong = tmp_path / "kepler.toml"
        wrong.write_text(KEPLER.read_text().replace("q = { r = 1.0, phi = 0.0 }", "q = [1.0, 0.0, 3.0]"))
        ddirac.load(wrong)
    assert "`q0` has 3 entries, but the system has 2 coordinates" in str(argument.value)
    assert "`initial.q` has 3 entries, but the system has 2 coordinates" in str(spec.value)

    with pytest.raises(ddirac.Error, match="`p0` gives a value for `z`, which is not a coordinate"):
        ddirac.simulate(system, q0=Q0, p0={"r": 0.0, "z": 1.0}, step=0.002, steps=5)
    with pytest.raises(ddirac.Error, match="`steps` must be at least 1"):
        ddirac.simulate(system, q0=Q0, p0=P0, step=0.002, steps=0)
    with pytest.raises(ddirac.Error, match="more than the 9007199254740992"):
        ddirac.simulate(system, q0=Q0, p0=P0, step=1e-300, duration=1.0)
