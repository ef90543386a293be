"""Text systems of 24 and 50 coordinates against the built-in chain of pendula, from Python."""

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
    # Python threads may have small stacks; a step of 50 coordinates needs about 3 MiB.
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


def test_a_size_the_engine_is_not_built_for_is_refused_with_the_sizes_it_is():
    with pytest.raises(ddirac.Error, match="17 coordinates; text systems are built for 1–16, 20, 24, 32, 40, 50"):
        text_chain(17)
