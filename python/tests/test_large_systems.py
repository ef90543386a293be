"""Text systems of many coordinates from Python: against the built-in chain of pendula, and against exact
solutions between the engine's sizes and above them (in a dimension chosen at run time)."""

import math
import threading

import numpy as np
import pytest

import ddirac


def text_chain(links):
    """The chain of ``links`` pendula written as text, with the running sums of the built-in's Lagrangian."""
    definitions = {}
    for i in range(1, links + 1):
        before = (lambda name: f"{name}{i - 1} + ") if i > 1 else (lambda name: "")
        definitions[f"vx{i}"] = f"{before('vx')}th{i}_dot*cos(th{i})"
        definitions[f"vy{i}"] = f"{before('vy')}th{i}_dot*sin(th{i})"
        definitions[f"d{i}"] = f"{before('d')}cos(th{i})"
    speeds = " + ".join(f"vx{i}^2 + vy{i}^2" for i in range(1, links + 1))
    depths = " + ".join(f"d{i}" for i in range(1, links + 1))
    names = [f"th{i}" for i in range(1, links + 1)]
    return ddirac.System(lagrangian=f"0.5*m*l^2*({speeds}) + g*m*l*({depths})", shape=names, angles=names,
                         definitions=definitions, parameters={"m": 1.0, "l": 1.0, "g": 9.8})


@pytest.mark.parametrize("links", [24, 50])
def test_a_text_chain_runs_as_the_built_in_chain(links):
    q0 = [0.5 * math.sin(math.pi * i / (links + 1)) for i in range(1, links + 1)]
    runs = [ddirac.simulate(system, q0=q0, p0=[0.0] * links, step=0.005, steps=100, derivatives="dual")
            for system in (text_chain(links), ddirac.System.builtin("pendulum_chain", links=links))]
    assert runs[0].q.shape == (101, links)
    assert np.abs(runs[1].q[-1] - runs[1].q[0]).max() > 1e-2
    np.testing.assert_allclose(runs[0].q, runs[1].q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(runs[0].p, runs[1].p, rtol=0, atol=1e-11)


def test_a_chain_of_fifty_runs_on_a_small_thread():
    # Python threads may have small stacks; a step of 50 coordinates with arrays on the stack would need
    # about 3 MiB (the built-in chain of 50 runs in a dimension chosen at run time, on the heap).
    threading.stack_size(1 << 20)
    result = {}
    try:
        thread = threading.Thread(target=lambda: result.setdefault(
            "run", ddirac.simulate(ddirac.System.builtin("pendulum_chain", links=50), q0=[0.3] * 50,
                                   p0=[0.0] * 50, step=0.005, steps=5, derivatives="dual")))
        thread.start()
        thread.join()
    finally:
        threading.stack_size(0)
    assert result["run"].q.shape == (6, 50)


@pytest.mark.parametrize("n", [17, 120])
def test_oscillators_follow_the_midpoint_rules_exact_rotation(n):
    # 17 and 120 coordinates run in a dimension chosen at run time (above the largest fixed size, 16);
    # each oscillator turns by 2 atan(ωh/2) per step, exactly, under the midpoint rule.
    h, steps = 0.02, 500
    omegas = [1.0 + i / n for i in range(n)]
    lagrangian = " + ".join(f"0.5*(x{i}_dot^2 - {w * w}*x{i}^2)" for i, w in enumerate(omegas))
    system = ddirac.System(lagrangian=lagrangian, shape=[f"x{i}" for i in range(n)])
    assert len(system.coordinates) == n
    run = ddirac.simulate(system, q0=[1.0] * n, p0=[0.0] * n, step=h, steps=steps, rule="midpoint")
    assert run.q.shape == (steps + 1, n) and run.p.shape == (steps + 1, n)
    k = np.arange(steps + 1)[:, None]
    exact = np.cos(2.0 * k * np.arctan(np.array(omegas) * h / 2.0))
    np.testing.assert_allclose(run.q, exact, rtol=0, atol=1e-11)
