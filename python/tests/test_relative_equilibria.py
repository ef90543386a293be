"""ddirac.relative_equilibria and ddirac.relative_equilibrium_family: the conical pendulum against its closed
form (μ² = m²gl³ sin⁴θ*/cos θ*, ω² = g(1 + 3cos²θ*)/(l cos θ*)), the same numbers as ``ddirac equilibria``
(and its ``--family``), and wrong inputs refused."""

import json
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import ddirac
from command_line import built

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def pendulum():
    return ddirac.System("0.5*m*l^2*(theta_dot^2 + sin(theta)^2*phi_dot^2) + m*g*l*cos(theta)", shape=["theta"],
                         group=["phi"], angles=["theta", "phi"], parameters={"m": 1.0, "l": 1.0, "g": 9.8})


def closed_form(mu, g=9.8):
    lo, hi = 1e-6, 1.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if np.sin(mid) ** 4 / np.cos(mid) < mu * mu / g:
            lo = mid
        else:
            hi = mid
    theta = 0.5 * (lo + hi)
    return theta, np.sqrt(g * (1 + 3 * np.cos(theta) ** 2) / np.cos(theta))


def test_the_conical_pendulum_converges_at_order_2_with_its_frequency():
    theta_star, omega = closed_form(1.6)
    errors = []
    for h in (0.01, 0.005, 0.0025):
        found = ddirac.relative_equilibria(pendulum(), momentum=[1.6], guess={"theta": 1.0}, step=h)
        assert isinstance(found, ddirac.RelativeEquilibrium) and found.stable
        assert found.shape_names == ["theta"] and found.group_names == ["phi"]
        assert found.multipliers.shape == (2, 2)
        assert np.abs(np.hypot(found.multipliers[:, 0], found.multipliers[:, 1]) - 1).max() < 1e-10
        errors.append(abs(found.shape[0] - theta_star))
        if h == 0.0025:
            assert abs(found.frequencies[1] - omega) < 1e-3 * omega
    # Without an atlas the main chart's θ stays constant at a conical motion, and the midpoint rule's
    # equation for it is the continuous one: the fixed point is exact. (The example's atlas, in
    # ddirac equilibria's test, gives order 2.)
    assert max(errors) < 1e-12, errors


def test_python_and_the_command_line_find_the_same_equilibrium(tmp_path):
    out = tmp_path / "eq"
    sets = ["initial.q.theta=1.0", "initial.p.phi=1.6", "initial.p.theta=0.0", "method.atlas=false"]
    args = [built(), "equilibria", str(EXAMPLES / "spherical_pendulum.toml"), "--out", str(out), "--quiet"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True)
    written = json.loads((out / "equilibria.json").read_text())["equilibria"][0]
    found = ddirac.relative_equilibria(pendulum(), momentum={"phi": 1.6}, guess=[1.0], step=0.005, reduced=True)
    assert written["shape"]["theta"] == found.shape[0]
    assert written["group_velocity"] == found.group_velocity.tolist()
    assert written["multipliers"] == found.multipliers.tolist()
    assert written["stable"] is found.stable


def test_wrong_inputs_are_refused_naming_them():
    system = pendulum()
    with pytest.raises(ddirac.Error, match="`momentum` has 2 values"):
        ddirac.relative_equilibria(system, momentum=[1.0, 2.0], guess=[1.0], step=0.01)
    with pytest.raises(ddirac.Error, match="`guess` names 'psi'"):
        ddirac.relative_equilibria(system, momentum=[1.0], guess={"psi": 1.0}, step=0.01)
    with pytest.raises(ddirac.Error, match="not a finite number"):
        ddirac.relative_equilibria(system, momentum=[float("nan")], guess=[1.0], step=0.01)
    with pytest.raises(ddirac.Error, match="multiplier 1"):
        free = ddirac.System("0.5*x_dot^2", shape=["x"])
        ddirac.relative_equilibria(free, momentum=[], guess=[0.0], step=0.1)
    with pytest.raises(ddirac.Error, match="rigid bodies"):
        ddirac.relative_equilibria(ddirac.System.builtin("rigid_body"), momentum=[], guess=[], step=0.1)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ddirac.relative_equilibria(system, momentum=[1.6], guess=[1.0], step=1.0)
    assert any("turns by more than π/2" in str(w.message) for w in caught)


def test_the_conical_pendulum_family_follows_its_closed_form():
    values = np.linspace(0.8, 3.0, 12)
    family = ddirac.relative_equilibrium_family(pendulum(), along="phi", values=values, guess={"theta": 0.5},
                                                step=0.0025)
    assert isinstance(family, ddirac.RelativeEquilibriumFamily) and len(family) == 12
    assert family.ended is None and family.stability_changes == []
    assert family.shape.shape == (12, 1) and family.momentum.shape == (12, 1)
    assert family.multipliers.shape == (12, 2, 2) and family.frequencies.shape == (12, 2)
    assert family.stable.dtype == bool and family.stable.all()
    np.testing.assert_array_equal(family.values, values)
    for k, mu in enumerate(values):
        theta_star, omega = closed_form(mu)
        # Without an atlas the midpoint rule's fixed point is the continuous one (see above).
        assert abs(family.shape[k, 0] - theta_star) < 1e-10, (mu, family.shape[k, 0], theta_star)
        assert abs(family.frequencies[k, 1] - omega) < 1e-3 * omega, (mu, family.frequencies[k], omega)
        # A member is the equilibrium a search on its own level finds.
        alone = ddirac.relative_equilibria(pendulum(), momentum=[mu], guess=[theta_star], step=0.0025)
        assert abs(alone.shape[0] - family.shape[k, 0]) < 1e-12
        # The conical motion turns at φ̇ = μ / sin²θ*.
        assert abs(family.group_velocity[k, 0] - mu / np.sin(theta_star) ** 2) < 1e-6 * mu / np.sin(theta_star) ** 2


def test_a_family_passes_its_fold_onto_the_other_branch():
    # Circular orbits in the field −1/r − a/r³: r² − μ² r + 3a = 0, outer stable, inner unstable, meeting
    # at the fold μ⁴ = 12a, r = √(3a). The midpoint rule's fixed point is the exact circle here.
    a = 0.1
    orbits = ddirac.System("0.5*(r_dot^2 + r^2*phi_dot^2) + 1/r + a/r^3", shape=["r"], group=["phi"],
                           angles=["phi"], parameters={"a": a})
    values = np.linspace(1.2, 1.0, 11)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        family = ddirac.relative_equilibrium_family(orbits, along="phi", values=values, guess={"r": 1.0}, step=0.01)
    assert family.ended is None and len(family.folds) == 1
    fold = family.folds[0]
    assert abs(fold.momentum - (12 * a) ** 0.25) < 1e-9 and abs(fold.shape[0] - np.sqrt(3 * a)) < 1e-6
    outer = fold.next_member
    assert outer == 8  # μ = 1.20 … 1.06 above the fold (1.0466); the inner circles over the same values
    np.testing.assert_allclose(family.values, np.concatenate([values[:outer], values[:outer][::-1]]), atol=1e-12)
    root = np.sqrt(family.values ** 4 - 12 * a)
    expected = np.where(np.arange(len(family)) < outer, family.values ** 2 + root, family.values ** 2 - root) / 2
    np.testing.assert_allclose(family.shape[:, 0], expected, rtol=1e-10)
    np.testing.assert_array_equal(family.stable, np.arange(len(family)) < outer)
    assert "a fold at 1.0466" in repr(family)


def test_python_and_the_command_line_continue_the_same_family(tmp_path):
    out = tmp_path / "family"
    sets = ["initial.q.theta=0.5", "initial.p.phi=0.8", "initial.p.theta=0.0", "method.atlas=false"]
    args = [built(), "equilibria", str(EXAMPLES / "spherical_pendulum.toml"), "--out", str(out), "--quiet",
            "--family", "phi=0.8:3.0:12"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True)
    written = json.loads((out / "equilibria.json").read_text())["equilibria"]
    family = ddirac.relative_equilibrium_family(pendulum(), along="phi", values=np.linspace(0.8, 3.0, 12),
                                                guess=[0.5], step=0.005, reduced=True)  # the spec's step
    assert len(written) == len(family)
    for member, row in zip(written, family.members):
        assert abs(member["shape"]["theta"] - row.shape[0]) < 1e-12
        assert member["stable"] is row.stable


def test_wrong_family_inputs_are_refused_naming_them():
    system = pendulum()
    with pytest.raises(ddirac.Error, match="`theta` is not a group coordinate"):
        ddirac.relative_equilibrium_family(system, along="theta", values=[1.0, 2.0], guess=[0.5], step=0.01)
    with pytest.raises(ddirac.Error, match="`values` is empty"):
        ddirac.relative_equilibrium_family(system, along="phi", values=[], guess=[0.5], step=0.01)
    with pytest.raises(ddirac.Error, match="not a finite number"):
        ddirac.relative_equilibrium_family(system, along="phi", values=[1.0, float("inf")], guess=[0.5], step=0.01)
    with pytest.raises(ddirac.Error, match="one-dimensional"):
        ddirac.relative_equilibrium_family(system, along="phi", values=[[1.0, 2.0]], guess=[0.5], step=0.01)
    with pytest.raises(ddirac.Error, match="sequence of numbers"):
        ddirac.relative_equilibrium_family(system, along="phi", values=["one"], guess=[0.5], step=0.01)
    # A momentum level that names `along` has that entry replaced by the first value.
    family = ddirac.relative_equilibrium_family(system, along="phi", values=[1.6], momentum={"phi": 99.0},
                                                guess=[1.0], step=0.0025)
    assert family.values.tolist() == [1.6] and abs(family.shape[0, 0] - closed_form(1.6)[0]) < 1e-10
    with pytest.raises(ddirac.Error, match="must be the name"):
        ddirac.relative_equilibrium_family(system, along=0, values=[1.0], guess=[0.5], step=0.01)
    with pytest.raises(ddirac.Error, match="rigid bodies"):
        ddirac.relative_equilibrium_family(ddirac.System.builtin("rigid_body"), along="x", values=[1.0], guess=[],
                                           step=0.1)
