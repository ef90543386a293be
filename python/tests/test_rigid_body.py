"""Rigid bodies from Python: ``System.builtin("rigid_body")``, ``simulate(body, R0=..., Pi0=.../Omega0=...)``
with ``run.R`` (rows, 3, 3) and ``run.Pi`` (rows, 3), checked against Euler's equations integrated here
by RK4, the reduced run against the unreduced one, the command line's run of the same spec, and every
wrong input refused with a message naming it."""

import json
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import ddirac
from command_line import built


def euler_rk4(inertia, mgc, R0, Pi0, T, n, rotors=(0.0, 0.0, 0.0)):
    """Π̇ = Π × Ω + Γ × (m g c), Γ = Rᵀ e3, Ṙ = R Ω̂, Ω = I⁻¹(Π − rotors) (a gyrostat whose rotors
    carry the constant momenta `rotors`), by RK4 with n steps."""
    inertia, mgc, rotors = np.asarray(inertia, float), np.asarray(mgc, float), np.asarray(rotors, float)

    def field(R, Pi):
        omega = (Pi - rotors) / inertia
        hat = np.array([[0, -omega[2], omega[1]], [omega[2], 0, -omega[0]], [-omega[1], omega[0], 0]])
        return R @ hat, np.cross(Pi, omega) + np.cross(R[2], mgc)

    h = T / n
    R, Pi = np.array(R0, float), np.array(Pi0, float)
    for _ in range(n):
        k1 = field(R, Pi)
        k2 = field(R + h / 2 * k1[0], Pi + h / 2 * k1[1])
        k3 = field(R + h / 2 * k2[0], Pi + h / 2 * k2[1])
        k4 = field(R + h * k3[0], Pi + h * k3[1])
        R = R + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        Pi = Pi + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return R, Pi


def tilted(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def test_a_free_body_follows_eulers_equations_and_reduces():
    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=2.0, I3=3.0, m=0.0)
    assert isinstance(body, ddirac.RigidBody) and isinstance(body, ddirac.System)
    assert body.symmetry == "SO(3)" and body.parameters["I2"] == 2.0 and body.coordinates == []
    run = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], step=0.01, duration=5.0, order=4, every=10)
    assert isinstance(run, ddirac.RigidRun)
    assert run.R.shape == (51, 3, 3) and run.Pi.shape == (51, 3) and run.momentum_map.shape == (51, 3)
    R, Pi = euler_rk4([1, 2, 3], [0, 0, 0], np.eye(3), [0.01, 4.0, 0.03], 5.0, 20_000)
    assert np.abs(run.R[-1] - R).max() < 1e-6 and np.abs(run.Pi[-1] - Pi).max() < 1e-6
    # R stays a rotation; R Π and |Π| are kept to round-off.
    assert np.abs(np.einsum("kji,kjl->kil", run.R, run.R) - np.eye(3)).max() < 1e-14
    assert np.abs(run.momentum_map - run.momentum_map[0]).max() < 1e-13
    assert np.allclose(run.momentum_map, np.einsum("kij,kj->ki", run.R, run.Pi), atol=1e-14)
    assert np.abs(np.linalg.norm(run.Pi, axis=1) / np.linalg.norm(run.Pi[0]) - 1).max() < 1e-13
    assert run.summary["final"]["R"] == run.R[-1].tolist() and run.summary["final"]["Pi"] == run.Pi[-1].tolist()
    reduced = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], step=0.01, duration=5.0, order=4,
                              every=10, reduced=True)
    assert np.abs(reduced.R - run.R).max() < 1e-12 and np.abs(reduced.Pi - run.Pi).max() < 1e-12
    assert reduced.summary["method"]["reduced"] is True


def test_a_heavy_top_follows_eulers_equations_and_refuses_reduction():
    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=1.3, I3=0.4, m=1.0, g=9.8, c1=0.05, c3=0.5)
    assert body.symmetry == "vertical"
    run = ddirac.simulate(body, R0=tilted(0.3), Pi0=[0.3, -0.2, 1.5], step=0.005, duration=3.0, order=4, every=20)
    R, Pi = euler_rk4([1, 1.3, 0.4], [0.05 * 9.8, 0, 0.5 * 9.8], tilted(0.3), [0.3, -0.2, 1.5], 3.0, 30_000)
    assert np.abs(run.R[-1] - R).max() < 1e-6 and np.abs(run.Pi[-1] - Pi).max() < 1e-6
    assert np.abs(run.momentum_map[:, 2] - run.momentum_map[0, 2]).max() < 1e-13
    with pytest.raises(ddirac.Error, match="reduction by SO\\(3\\) needs a Lagrangian invariant"):
        ddirac.simulate(body, R0=np.eye(3), Pi0=[0, 0, 1], step=0.01, steps=10, reduced=True)


def test_python_and_the_command_line_give_the_same_bits(tmp_path):
    spec = tmp_path / "free.toml"
    spec.write_text('system = "rigid_body"\n[parameters]\nI1 = 1.0\nI2 = 2.0\nI3 = 3.0\nm = 0.0\n'
                    '[method]\norder = 6\n[time]\nstep = 0.02\nsteps = 300\n[initial]\n'
                    'R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\nPi = [0.1, 2.0, 0.3]\n[output]\nevery = 7\n')
    subprocess.run([built(), "run", str(spec), "--out", str(tmp_path / "out"), "--quiet"], check=True)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=2.0, I3=3.0, m=0.0)
    run = ddirac.simulate(body, R0=np.eye(3), Pi0=[0.1, 2.0, 0.3], step=0.02, steps=300, order=6, every=7)
    assert summary["final"]["R"] == run.summary["final"]["R"] and summary["final"]["Pi"] == run.summary["final"]["Pi"]
    header = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()[0].split(",")
    assert header == list(run.columns())
    assert len(run) == 44  # rows 0, 7, ..., 294 and the last


def test_wrong_inputs_are_refused_naming_them():
    body = ddirac.System.builtin("rigid_body", m=0.0)
    grid = dict(step=0.01, steps=10)
    cases = [
        (dict(R0=[[1, 0.1, 0], [0, 1, 0], [0, 0, 1]], Pi0=[0, 1, 0]), "not a rotation"),
        (dict(R0=np.diag([-1.0, 1.0, 1.0]), Pi0=[0, 1, 0]), "det R = -1"),
        (dict(R0=np.eye(2), Pi0=[0, 1, 0]), "`R0` must be a 3 × 3 rotation"),
        (dict(R0=np.eye(3), Pi0=[0, 1]), "`Pi0` must be 3 numbers"),
        (dict(R0=np.eye(3), Pi0=[0, 1, 0], Omega0=[0, 1, 0]), "not both"),
        (dict(R0=np.eye(3)), "give the body angular momentum `Pi0` or the body angular velocity `Omega0`"),
        (dict(Pi0=[0, 1, 0]), "needs `R0`"),
        (dict(R0=np.eye(3), Omega0=[0, np.nan, 0]), "not finite"),
        (dict(R0=np.eye(3), Omega0=[1e200, 0, 0]), "overflows"),
        (dict(R0=np.eye(3), Omega0=[0, 1, 0], variant="minus"), "no \\(\\+\\)/\\(−\\) choice"),
        (dict(R0=np.eye(3), Omega0=[0, 1, 0], connection=[[0.0]]), "takes no `connection`"),
        (dict(R0=np.eye(3), Omega0=[0, 1, 0], atlas=False), "takes no `atlas`"),
        (dict(R0=np.eye(3), Omega0=[0, 1, 0], order=4, rule="left"), "order"),
        (dict(R0=np.eye(3), Omega0=[0, 1, 0], wrap_angles=True), "`wrap_angles` has no meaning"),
        (dict(q0=[0.0], R0=np.eye(3), Omega0=[0, 1, 0]), "has no shape coordinates"),
    ]
    for arguments, message in cases:
        with pytest.raises(ddirac.Error, match=message):
            ddirac.simulate(body, **{**grid, **arguments})
    with pytest.raises(ddirac.Error, match="positive"):
        ddirac.System.builtin("rigid_body", I1=0.0)
    with pytest.raises(ddirac.Error, match="unknown"):
        ddirac.System.builtin("rigid_body", I4=1.0)
    with pytest.raises(ddirac.Error, match="does not take rigid bodies yet"):
        ddirac.check(body, q0=[], step=0.01, steps=10)
    kepler = ddirac.System.builtin("kepler")
    with pytest.raises(ddirac.Error, match="initial data of a rigid body"):
        ddirac.simulate(kepler, R0=np.eye(3), Pi0=[0, 0, 1], step=0.01, steps=10)
    with pytest.raises(ddirac.Error, match="`q0` is missing"):
        ddirac.simulate(kepler, step=0.01, steps=10)


def test_a_step_that_does_not_resolve_the_rotation_warns():
    body = ddirac.System.builtin("rigid_body", m=0.0)
    with pytest.warns(ddirac.UnderResolvedWarning, match="turned by"):
        run = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 300.0, 0.01], step=0.01, steps=100)
    assert [w["kind"] for w in run.summary["warnings"]] == ["under_resolved"]
    with warnings.catch_warnings():
        warnings.simplefilter("error", ddirac.RunWarning)
        ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 3.0, 0.01], step=0.01, steps=100)


def test_builtin_systems_lists_the_rigid_body():
    assert "rigid_body" in ddirac.builtin_systems()


SATELLITE = "0.5*(J1*Omega1^2 + J2*Omega2^2 + J3*Omega3^2) + 0.5*(K1*w1^2 + K2*w2^2 + K3*w3^2)"
ROTOR_RATES = {"w1": "Omega1 + a1_dot", "w2": "Omega2 + a2_dot", "w3": "Omega3 + a3_dot"}
MOMENTS = {"J1": 1.0, "J2": 2.0, "J3": 3.0, "K1": 0.1, "K2": 0.1, "K3": 0.1}


def satellite(**changes):
    arguments = dict(symmetry="SO(3)", shape=["a1", "a2", "a3"], angles=["a1", "a2", "a3"],
                     definitions=ROTOR_RATES, parameters=MOMENTS, name="satellite with three rotors")
    arguments.update(changes)
    return ddirac.RigidBody(arguments.pop("lagrangian", SATELLITE), **arguments)


def test_a_satellite_with_rotors_written_as_text_follows_the_gyrostat():
    body = satellite()
    assert body.coordinates == ["a1", "a2", "a3"] and body.angles == ["a1", "a2", "a3"] and body.symmetry == "SO(3)"
    run = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], q0=[0, 0, 0], v0={"a2": 30.0, "a1": 0, "a3": 0},
                          step=0.005, duration=10.0, order=4, every=100, reduced=True)
    assert run.q.shape == (21, 3) and run.p.shape == (21, 3) and run.coordinates == ["a1", "a2", "a3"]
    rotors = [0.001, 3.2, 0.001]
    R, Pi = euler_rk4([1, 2, 3], [0, 0, 0], np.eye(3), [0.011, 7.2, 0.031], 10.0, 20_000, rotors=rotors)
    assert np.abs(run.R[-1] - R).max() < 3e-8 and np.abs(run.Pi[-1] - Pi).max() < 3e-8
    assert np.abs(run.p - rotors).max() < 1e-10
    assert list(run.columns())[13:19] == ["a1", "a2", "a3", "p_a1", "p_a2", "p_a3"]
    unreduced = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], q0=[0, 0, 0], v0=[0, 30, 0],
                                step=0.005, duration=10.0, order=4, every=100)
    assert np.abs(unreduced.R - run.R).max() < 1e-11 and np.abs(unreduced.q - run.q).max() < 1e-9


def test_the_satellite_example_runs_the_same_from_python_and_the_command_line(tmp_path):
    out = tmp_path / "out"
    subprocess.run([built(), "run", "../../examples/satellite_rotors.toml", "--out", str(out), "--quiet",
                    "--set", "time.duration=2.0"], check=True, cwd=str(Path(__file__).parent))
    summary = json.loads((out / "summary.json").read_text())
    run = ddirac.simulate(satellite(), R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], q0=[0, 0, 0], v0=[0, 30, 0],
                          step=0.01, duration=2.0, reduced=True, every=10)
    assert run.summary["final"] == summary["final"]
    assert run.summary["system"] == summary["system"] == "satellite with three rotors"


def test_wrong_text_rigid_systems_are_refused_naming_the_cause():
    with pytest.raises(ddirac.Error, match="unknown symmetry"):
        satellite(symmetry="SO4")
    with pytest.raises(ddirac.ExpressionError, match="(?s)unknown name `Omgea1`.*the body angular velocity"):
        satellite(lagrangian="0.5*Omgea1^2 + K1*w1^2")
    with pytest.raises(ddirac.ExpressionError, match="`Omega1`"):
        satellite(parameters={**MOMENTS, "Omega1": 1.0})
    with pytest.raises(ddirac.Error, match="not a shape coordinate"):
        satellite(angles=["b"])
    body = satellite(lagrangian=SATELLITE + " - 9.8*R13")
    with pytest.raises(ddirac.InvarianceError, match="not invariant under its declared symmetry `SO\\(3\\)`"):
        ddirac.simulate(body, R0=np.eye(3), Omega0=[0, 1, 0], q0=[0, 0, 0], v0=[0, 0, 0], step=0.01, steps=10)
    body = satellite()
    grid = dict(R0=np.eye(3), step=0.01, steps=10)
    with pytest.raises(ddirac.Error, match="`Pi0` goes with the shape's momenta `p0`"):
        ddirac.simulate(body, Pi0=[0, 1, 0], q0=[0, 0, 0], v0=[0, 0, 0], **grid)
    with pytest.raises(ddirac.Error, match="`q0` is missing"):
        ddirac.simulate(body, Omega0=[0, 1, 0], v0=[0, 0, 0], **grid)
    with pytest.raises(ddirac.Error, match="p0. or .v0"):
        ddirac.simulate(body, Omega0=[0, 1, 0], q0=[0, 0, 0], **grid)
    with pytest.raises(ddirac.Error, match="3 entries|coordinate"):
        ddirac.simulate(body, Omega0=[0, 1, 0], q0=[0, 0], v0=[0, 0, 0], **grid)


def test_a_convergence_study_of_a_rigid_body_against_rk4():
    """``ddirac.convergence`` of a rigid body: each row's error (against its reference run) is within
    5 % of the distance of that run's R_N from RK4 of Euler's equations, and the orders are 2 and 4."""
    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=2.0, I3=3.0, m=0.0)
    R_exact, _ = euler_rk4((1.0, 2.0, 3.0), (0.0, 0.0, 0.0), np.eye(3), np.array([0.01, 4.0, 0.03]), 5.0, 20_000)
    for order, counts in ((2, [250, 500, 1000]), (4, [50, 100, 200])):
        table = ddirac.convergence(body, counts, 5.0, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], order=order)
        assert table["declared_order"] == order and table["verdict"] == "as declared", table["message"]
        for n, error in zip(counts, table["error"]):
            run = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], steps=n, duration=5.0, every=n,
                                  order=order)
            to_rk4 = np.linalg.norm(run.R[-1] - R_exact)
            assert abs(error - to_rk4) < 0.05 * to_rk4, (order, n, error, to_rk4)
    # A system in coordinates still needs q0; a rigid body's keys on it are refused.
    with pytest.raises(ddirac.Error, match="`q0` is missing"):
        ddirac.convergence(ddirac.System.builtin("kepler"), [10, 20], 1.0)


def test_an_ensemble_of_heavy_tops_gives_r_and_pi_arrays_equal_to_single_runs(tmp_path):
    spec = tmp_path / "top.toml"
    R0 = tilted(0.3)
    spec.write_text('system = "rigid_body"\n[parameters]\nI1 = 1.0\nI2 = 1.3\nI3 = 0.4\nm = 1.0\ng = 9.8\n'
                    'c1 = 0.05\nc3 = 0.5\n[method]\norder = 4\n[time]\nstep = 0.005\nduration = 2.0\n[initial]\n'
                    f'R = {json.dumps(R0.tolist())}\nPi = [0.3, -0.2, 1.5]\n[output]\nevery = 40\n')
    members = {"initial.Pi.3": [1.5, 1.2, -0.8], "parameters.c3": [0.5, 0.4, 0.6]}
    result = ddirac.ensemble(spec, members=members, trajectories=True)
    assert result.attitude and result.coordinates == []
    assert result.final_R.shape == (3, 3, 3) and result.final_Pi.shape == (3, 3)
    assert result.final_q.shape == (3, 0) and result.R.shape == (3, 11, 3, 3) and result.Pi.shape == (3, 11, 3)
    assert list(result.status) == ["ok"] * 3
    for k, (pi3, c3) in enumerate(zip(members["initial.Pi.3"], members["parameters.c3"])):
        body = ddirac.System.builtin("rigid_body", I1=1.0, I2=1.3, I3=0.4, m=1.0, g=9.8, c1=0.05, c3=c3)
        run = ddirac.simulate(body, R0=R0, Pi0=[0.3, -0.2, pi3], step=0.005, duration=2.0, order=4, every=40)
        # The member is the single run, bit for bit, rows and all.
        assert np.array_equal(result.R[k], run.R) and np.array_equal(result.Pi[k], run.Pi)
        assert np.array_equal(result.final_R[k], run.R[-1]) and np.array_equal(result.final_Pi[k], run.Pi[-1])
        R, Pi = euler_rk4([1, 1.3, 0.4], [0.05 * 9.8, 0, c3 * 9.8], R0, [0.3, -0.2, pi3], 2.0, 20_000)
        assert np.abs(result.final_R[k] - R).max() < 1e-6 and np.abs(result.final_Pi[k] - Pi).max() < 1e-6
    columns = result.columns()
    assert list(columns)[:4] == ["member", "status", "R11", "R12"] and np.array_equal(columns["Pi3"],
                                                                                     result.final_Pi[:, 2])
    with pytest.raises(ddirac.Error, match="the attitude R is a rotation"):
        ddirac.ensemble(spec, members={"initial.R.1": [1.0]})
    with pytest.raises(ddirac.Error, match="names no component"):
        ddirac.ensemble(spec, members={"initial.Pi.0": [1.0]})
