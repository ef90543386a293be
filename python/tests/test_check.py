"""ddirac.check: a run's hypotheses as data, and the verdict the run would give."""

import pathlib

import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_an_invariant_system_passes_and_its_run_would_go():
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    report = ddirac.check(dsp, q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=100, reduced=True)
    assert report["invariant"] and report["periodic"] and report["regular"]
    assert [f["coordinate"] for f in report["invariance"]] == ["vartheta1"]
    assert report["invariance"][0]["holds"] and report["invariance"][0]["deviation"] <= report["invariance_tolerance"]
    assert report["legendre_rank"] == report["coordinates"] == 4
    assert report["verdict"] == {"runs": True, "error": None, "warnings": []}


def test_a_system_that_is_not_invariant_is_found_out_without_integrating():
    pendulum = ddirac.System(lagrangian="0.5*theta_dot^2 + cos(theta)", group=["theta"], angles=["theta"])
    report = ddirac.check(pendulum, q0=[1.0], p0=[0.0], step=0.01, steps=10, reduced=True)
    assert not report["invariant"] and not report["invariance"][0]["holds"]
    assert report["invariance"][0]["deviation"] > 1e-3
    assert not report["verdict"]["runs"] and "theta" in report["verdict"]["error"]
    # Without the check, the run would go, with a warning.
    with pytest.warns(ddirac.NotInvariantWarning):
        unchecked = ddirac.check(pendulum, q0=[1.0], p0=[0.0], step=0.01, steps=10, reduced=True,
                                 check_invariance=False)
    assert unchecked["verdict"]["runs"] and [w["kind"] for w in unchecked["verdict"]["warnings"]] == ["not_invariant"]


def test_a_degenerate_lagrangian_reports_its_rank_and_the_primary_constraint():
    spec = ddirac.load(EXAMPLES / "point_vortices.toml")
    report = spec.check()
    assert report["legendre_rank"] < report["coordinates"] and not report["regular"]
    assert report["momentum_consistent"] and report["verdict"]["runs"]
