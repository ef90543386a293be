"""``sensitivities=True``: ``Run.sensitivity``, the tangent map d(q_N, p_N)/d(q_0, p_0), against central
differences of whole runs and ΦᵀJΦ = J; absent by default; the same matrix as summary.json's; refused for
a rigid body and in an ensemble."""

from pathlib import Path

import numpy as np
import pytest

import ddirac

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PENDULUM = ddirac.System.builtin("spherical_pendulum")
Q0, P0 = [0.3, 2.0], [0.5, 0.2]


def final(q0, p0, **method):
    run = ddirac.simulate(PENDULUM, q0=q0, p0=p0, step=0.01, steps=200, reduced=True, tolerance=1e-14, **method)
    return np.concatenate([run.q[-1], run.p[-1]]), run


def test_the_tangent_map_equals_central_differences_and_is_symplectic():
    _, run = final(Q0, P0, sensitivities=True)
    phi = run.sensitivity
    assert phi.shape == (4, 4)
    assert np.array_equal(phi, np.array(run.summary["sensitivity"]["state"]))
    n = 2
    J = np.block([[np.zeros((n, n)), np.eye(n)], [-np.eye(n), np.zeros((n, n))]])
    scale = max(1.0, np.abs(phi).max() ** 2)
    assert np.abs(phi.T @ J @ phi - J).max() < 1e-9 * scale
    x0 = np.array(Q0 + P0)
    fd = np.zeros((4, 4))
    for j in range(4):
        delta = 1e-6 * (1 + abs(x0[j]))
        plus, minus = x0.copy(), x0.copy()
        plus[j] += delta
        minus[j] -= delta
        fd[:, j] = (final(list(plus[:2]), list(plus[2:]))[0] - final(list(minus[:2]), list(minus[2:]))[0]) / (2 * delta)
    assert np.abs(phi - fd).max() < 1e-5 * np.abs(phi).max()


def test_no_sensitivity_unless_asked():
    _, run = final(Q0, P0)
    assert run.sensitivity is None
    assert "sensitivity" not in run.summary


def test_a_rigid_body_is_refused():
    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=2.0, I3=3.0)
    with pytest.raises(ddirac.Error, match="no tangent map"):
        ddirac.simulate(body, R0=np.eye(3), Pi0=[0.3, 2.0, 0.5], step=0.01, steps=10, sensitivities=True)


def test_an_ensemble_is_refused(tmp_path):
    spec = ddirac.load(EXAMPLES / "spherical_pendulum.toml",
                       overrides={"method.sensitivities": True, "time.duration": 0.1})
    with pytest.raises(ddirac.Error, match="sensitivities"):
        ddirac.ensemble(spec, {"initial.q.theta": [0.5, 0.6]})


def test_a_tangent_map_that_overflows_warns_sensitivity_lost():
    # A particle resting on a saddle, L = ½ẋ² + 50x²: the motion stays at x = 0, the tangent map grows as
    # μ^N, μ = (1 + hλ/2)/(1 − hλ/2) with λ = 10, and passes 1.8e308 near t = 70.8.
    saddle = ddirac.System(lagrangian="0.5*x_dot^2 + 50*x^2", shape=["x"])
    with pytest.warns(ddirac.SensitivityLostWarning, match="overflowed"):
        run = ddirac.simulate(saddle, q0=[0.0], v0=[0.0], step=0.01, steps=10000, sensitivities=True)
    assert run.q[-1][0] == 0.0
    assert not np.isfinite(run.sensitivity).any()
    lost = [w for w in run.summary["warnings"] if w["kind"] == "sensitivity_lost"]
    assert len(lost) == 1 and 70.0 < lost[0]["t"] < 71.5
