"""The exceptions: ddirac.Error and the subclass of each kind, with the data a handler needs."""

import pathlib

import pytest

import ddirac

DSP = pathlib.Path(__file__).resolve().parents[2] / "examples" / "double_spherical_pendulum.toml"


def test_the_hierarchy():
    for kind in (ddirac.SpecError, ddirac.ExpressionError, ddirac.InvarianceError, ddirac.ConvergenceError):
        assert issubclass(kind, ddirac.Error) and issubclass(kind, Exception)


def test_an_unknown_name_in_a_lagrangian_is_an_expression_error_with_its_span():
    with pytest.raises(ddirac.ExpressionError) as error:
        ddirac.System(lagrangian="0.5*x_dot^2 + yy", shape=["x"])
    e = error.value
    assert e.text == "0.5*x_dot^2 + yy" and e.text[e.span[0]:e.span[1]] == "yy"
    assert "Lagrangian" in e.origin and "yy" in str(e)


def test_a_bad_definition_names_the_definition_and_its_text():
    with pytest.raises(ddirac.ExpressionError) as error:
        ddirac.System(lagrangian="0.5*x_dot^2 - V", shape=["x"], definitions={"V": "x^2 +* 1"})
    e = error.value
    assert e.text == "x^2 +* 1" and "V" in e.origin and e.span is not None


def test_reducing_a_lagrangian_that_is_not_invariant_is_an_invariance_error():
    # θ is declared a group coordinate, but L depends on it through cos θ.
    pendulum = ddirac.System(lagrangian="0.5*theta_dot^2 + cos(theta)", group=["theta"], angles=["theta"])
    with pytest.raises(ddirac.InvarianceError, match="theta"):
        ddirac.simulate(pendulum, q0=[1.0], p0=[0.0], step=0.01, steps=10, reduced=True)


def test_a_failed_step_is_a_convergence_error_with_step_time_and_residual():
    with pytest.raises(ddirac.ConvergenceError) as error:
        ddirac.simulate(ddirac.System.builtin("double_spherical_pendulum"), q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1],
                        step=0.01, steps=10, max_iterations=1, tolerance=1e-16)
    e = error.value
    assert (e.step, e.t) == (0, 0.0) and e.residual > 0 and "Newton" in str(e)


def test_a_bad_spec_is_a_spec_error_and_a_failed_spec_run_a_convergence_error(tmp_path):
    with pytest.raises(ddirac.SpecError, match="unknown rule"):
        ddirac.load(DSP, overrides={"method.rule": "simpson"})
    spec = ddirac.load(DSP, overrides={"method.max_iterations": 1, "method.tolerance": 1e-16})
    with pytest.raises(ddirac.ConvergenceError):
        spec.run()
