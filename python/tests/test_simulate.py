"""ddirac from Python: runs against exact solutions, the unreduced flow and the conservation laws."""

import threading

import numpy as np
import pytest

import ddirac


def oscillator():
    """L = ½ẋ² − ½ω²x² with ω = 2, as text: x(t) = cos 2t from x = 1 at rest."""
    return ddirac.System(lagrangian="0.5*x_dot^2 - 0.5*w^2*x^2", shape=["x"], parameters={"w": 2.0},
                         exact={"x": "cos(w*t)"})


def test_a_text_oscillator_follows_its_exact_motion_to_second_order():
    errors = []
    for steps in (200, 400, 800):
        run = ddirac.simulate(oscillator(), q0=[1.0], p0=[0.0], steps=steps, duration=2.0)
        errors.append(abs(run.q[-1, 0] - np.cos(4.0)))
        assert run.summary["reference_error"] == pytest.approx(errors[-1], rel=1e-12)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.05), orders


@pytest.mark.parametrize("order, composition, counts", [(4, None, (20, 40, 80)), (6, None, (10, 20, 40)),
                                                       (8, None, (6, 9, 13)), (4, "triple-jump", (20, 40, 80))])
def test_compositions_of_the_text_oscillator_reach_their_orders(order, composition, counts):
    errors = []
    for steps in counts:
        run = ddirac.simulate(oscillator(), q0=[1.0], p0=[0.0], steps=steps, duration=2.0, order=order,
                              composition=composition)
        errors.append(abs(run.q[-1, 0] - np.cos(4.0)))
    h = 2.0 / np.array(counts, dtype=float)
    observed = np.log(np.array(errors[:-1]) / np.array(errors[1:])) / np.log(h[:-1] / h[1:])
    assert np.all(np.abs(observed - order) < 0.2), (observed, errors)
    assert run.summary["method"]["order"] == order


def test_a_composition_of_the_left_rule_is_refused():
    with pytest.raises(ddirac.Error, match="symmetric rule"):
        ddirac.simulate(oscillator(), q0=[1.0], p0=[0.0], steps=10, duration=1.0, rule="left", order=4)


def test_the_charged_particle_gyrates_as_in_the_paper():
    cp = ddirac.System.builtin("charged_particle")
    run = ddirac.simulate(cp, q0=[0, 0, 0, 0], v0=[1, 0, 1, 1], step=0.001, steps=2000, rule="midpoint",
                          reduced=True)
    t = run.t
    exact = np.stack([np.sin(t), np.cos(t) - 1.0, t], axis=1)
    assert np.max(np.abs(run.q[:, :3] - exact)) < 1e-6
    assert run.coordinates == ["q1", "q2", "q3", "theta"] and run.group == ["theta"]


def test_reduced_and_unreduced_runs_agree_and_the_momentum_map_is_exact():
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    common = dict(q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=1000)
    # In the paper's chart (no chart switches) the reduced run holds the momentum map exactly.
    paper = ddirac.simulate(dsp, reduced=True, atlas=False, **common)
    assert paper.summary["momentum_map"]["max_drift"] == 0.0 and paper.summary["chart_switches"] == 0
    reduced = ddirac.simulate(dsp, reduced=True, **common)
    unreduced = ddirac.simulate(dsp, reduced=False, **common)
    assert np.max(np.abs(reduced.q - unreduced.q)) < 1e-8
    # With the atlas, while both bobs are near the bottom the run is in a chart without group
    # coordinates or where charts overlap (glued unreduced steps, ddirac::blend): the momentum map is
    # conserved as far as the steps' L_d is invariant in floating point, a few 1e-12 of the momenta
    # (which reach 1e6) over 1000 steps.
    assert reduced.summary["chart_switches"] > 0
    scale = np.max(np.abs(reduced.p))
    drift = np.max(np.abs(reduced.momentum_map - reduced.momentum_map[0]))
    assert drift <= 2e-11 * scale and reduced.summary["momentum_map"]["max_drift"] <= 2e-11 * scale, drift / scale
    energy = reduced.energy
    assert np.max(np.abs(energy - energy[0])) / abs(energy[0]) < 1e-4


def test_arrays_have_one_row_per_kept_step_and_named_columns():
    run = ddirac.simulate(oscillator(), q0={"x": 1.0}, p0={"x": 0.0}, step=0.01, steps=100, every=7)
    rows = 100 // 7 + 2  # every 7th step from 0, and the last
    assert run.q.shape == (rows, 1) and run.p.shape == (rows, 1) and run.t.shape == (rows,)
    assert run.q.dtype == np.float64 and run.q.flags["C_CONTIGUOUS"] and run.q.flags["WRITEABLE"]
    # The arrays are the engine's buffers handed over, not copies: q is a (rows, n) view of the 1-D array
    # made on the buffer, whose memory the Rust vector (a capsule, not another array) keeps alive.
    owner = run.q.base
    assert isinstance(owner, np.ndarray) and owner.ndim == 1 and not isinstance(owner.base, np.ndarray)
    assert np.shares_memory(run.q, owner)
    run.q[0, 0] = 42.0  # writable, and the run's own
    assert run.t[-1] == pytest.approx(1.0) and np.isnan(run.discrete_energy[-1])
    assert not np.isnan(run.discrete_energy[:-1]).any()
    assert run.momentum_map.shape == (rows, 0)
    assert list(run.columns()) == ["t", "x", "p_x", "energy", "discrete_energy"]
    assert run.summary["steps"] == 100 and run.summary["step"] == 0.01
    assert run.summary["coordinates"] == ["x"] and run.summary["warnings"] == []


def test_a_system_from_text_equals_the_built_in_one():
    # examples/charged_particle_expression.toml: L = ½ m |q̇|² + ½ (A(q)·q̇ + θ̇)², A = (B0/2)(−y, x, 0).
    text = ddirac.System(
        lagrangian="0.5*m*(x_dot^2 + y_dot^2 + z_dot^2) + 0.5*(Ax*x_dot + Ay*y_dot + theta_dot)^2",
        shape=["x", "y", "z"], group=["theta"], angles=["theta"],
        definitions={"Ax": "-B0/2*y", "Ay": "B0/2*x"}, parameters={"m": 1.0, "B0": 1.0},
        exact={"x": "sin(t)", "y": "cos(t) - 1", "z": "t"}, name="charged particle")
    built_in = ddirac.System.builtin("charged_particle")
    common = dict(q0=[0, 0, 0, 0], p0=[1, 0, 1, 1], steps=100, duration=20.0, rule="left", reduced=True)
    a, b = ddirac.simulate(text, **common), ddirac.simulate(built_in, **common)
    assert np.max(np.abs(a.q - b.q)) < 1e-12 and np.max(np.abs(a.p - b.p)) < 1e-12
    # Table 1 of the paper, N = 100: the error ‖q(T) − q_N‖ is printed as 0.06626.
    assert round(a.summary["reference_error"], 5) == 0.06626
    assert a.summary["system"] == "charged particle" and a.summary["parameters"] == {"m": 1.0, "B0": 1.0}


@pytest.mark.parametrize("call, message", [
    (lambda: ddirac.System.builtin("pendulum"), "no built-in system `pendulum`"),
    (lambda: ddirac.System.builtin("pendulum_chain", length=2), "has no parameter `length`"),
    (lambda: ddirac.System(lagrangian="0.5*x_dot^2 + y", shape=["x"]), "y"),
    (lambda: ddirac.simulate(oscillator(), q0=[1, 2], p0=[0], step=0.1, steps=3), "`q0` has 2 entries"),
    (lambda: ddirac.simulate(oscillator(), q0=[np.nan], p0=[0], step=0.1, steps=3), "`q0` entry for `x` is not finite"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], v0=[0], step=0.1, steps=3), "takes `p0` or `v0`, not both"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], step=0.1), "two of `step`, `steps`"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], step=0.3, duration=1.0), "not a whole number"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], step=0.1, steps=3, rule="simpson"), "`rule`"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], step=0.1, steps=3, tolerence=1e-9), "tolerence"),
    (lambda: ddirac.simulate(oscillator(), q0=[1], p0=[0], step=0.1, steps=3, reduced=True), "group"),
])
def test_bad_input_raises_ddirac_error_naming_the_cause(call, message):
    with pytest.raises(ddirac.Error) as error:
        call()
    assert message in str(error.value)
    assert issubclass(ddirac.Error, Exception)


def test_a_failed_step_raises_with_the_step_and_time():
    # A step far too long for Newton's method with one iteration.
    with pytest.raises(ddirac.Error, match=r"step 0 \(t = 0, h = 0.01\)"):
        ddirac.simulate(ddirac.System.builtin("double_spherical_pendulum"), q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1],
                        step=0.01, steps=10, max_iterations=1, tolerance=1e-16)


def test_the_gil_is_released_while_a_run_integrates():
    chain = ddirac.System.builtin("pendulum_chain", links=8)
    done = threading.Event()
    result = {}

    def work():
        result["run"] = ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=20000,
                                        derivatives="dual")
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    ticks = 0
    while not done.is_set():
        ticks += 1
    thread.join()
    # With the GIL held for the whole run this thread could not count at all while it lasts.
    assert ticks > 10_000, ticks
    assert result["run"].q.shape == (20001, 8)


def test_ctrl_c_stops_a_run_within_a_fraction_of_a_second():
    import _thread
    import signal
    import time

    chain = ddirac.System.builtin("pendulum_chain", links=8)
    # Python's own Ctrl-C handler, whatever this process was started with: a process started in the
    # background by a non-interactive shell ignores SIGINT, and interrupt_main then does nothing.
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        # About 5 s uninterrupted; Ctrl-C (simulated by interrupt_main) after 0.3 s.
        timer = threading.Timer(0.3, _thread.interrupt_main)
        timer.start()
        start = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=1_000_000, derivatives="dual",
                            every=1000)
        stopped = time.monotonic() - start
        timer.join()
    finally:
        signal.signal(signal.SIGINT, handler)
    # Without the watch the exception would come only when the run returned, seconds later.
    assert stopped < 0.3 + 0.5, stopped
    # The stop request does not outlive the interrupted run.
    assert len(ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=10)) == 11


def test_progress_is_reported_about_ten_times_a_second_and_a_raising_callback_stops_the_run():
    chain = ddirac.System.builtin("pendulum_chain", links=8)
    seen = []
    run = ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=100_000, derivatives="dual",
                          every=1000, progress=lambda k, steps: seen.append((k, steps)))
    assert len(run) == 101 and seen, "a run of about half a second reports"
    assert all(steps == 100_000 for _, steps in seen) and [k for k, _ in seen] == sorted(k for k, _ in seen)

    class Stop(Exception):
        pass

    def stop(k, steps):
        raise Stop(k)

    with pytest.raises(Stop):
        ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=100_000, derivatives="dual",
                        progress=stop)


def test_without_tqdm_the_bar_is_a_line_on_stderr_that_is_cleared_at_the_end(capsys, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # as if tqdm were not installed
    chain = ddirac.System.builtin("pendulum_chain", links=8)
    ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=100_000, derivatives="dual", every=1000,
                    progress=True)
    err = capsys.readouterr().err
    assert "ddirac [" in err and "/100000" in err and err.endswith("\r"), repr(err[-80:])
    # Off by default outside a notebook.
    ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=100_000, derivatives="dual", every=1000)
    assert capsys.readouterr().err == ""


def test_two_runs_in_two_python_threads_overlap_in_time():
    import time

    chain = ddirac.System.builtin("pendulum_chain", links=8)
    spans = {}

    def work(name):
        stamps = []
        ddirac.simulate(chain, q0=[0.3] * 8, p0=[0.0] * 8, step=0.005, steps=100_000, derivatives="dual",
                        every=1000, progress=lambda k, steps: stamps.append(time.monotonic()))
        spans[name] = (stamps[0], stamps[-1])

    threads = [threading.Thread(target=work, args=(name,)) for name in ("a", "b")]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    (a0, a1), (b0, b1) = spans["a"], spans["b"]
    # Each reported progress while the other was running: with the GIL held for a whole run, one would
    # start only after the other ended.
    assert a0 < b1 and b0 < a1, spans
