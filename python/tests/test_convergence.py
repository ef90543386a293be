"""ddirac.convergence: the error table and the observed order, as `ddirac convergence` gives them."""

import pathlib

import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_the_charged_particles_table_is_the_papers_table_1_against_the_exact_solution():
    # The coarsest row, h = 2, turns theta by 2 rad a step, and says so.
    with pytest.warns(ddirac.UnderResolvedWarning) as record:
        table = ddirac.load(EXAMPLES / "charged_particle.toml").convergence([10, 50, 100, 200])
    assert [w.message.step_sizes for w in record] == [[2.0]] and table["warnings"] == {"under_resolved": [2.0]}
    assert table["reference"] == "exact" and table["steps"] == [10, 50, 100, 200]
    printed = [1.6781, 0.25971, 0.06626, 0.01664]
    assert [float(f"{e:.4g}") for e in table["error"]] == [float(f"{p:.4g}") for p in printed]
    assert table["order"][0] is None and table["order"][-1] == pytest.approx(2.0, abs=0.01)


def test_without_an_exact_solution_the_reference_is_a_finer_run_and_the_order_is_two():
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    table = ddirac.convergence(dsp, [100, 200, 400], duration=1.0, q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1],
                               reduced=True)
    assert table["reference"] == 3200
    assert all(abs(p - 2.0) < 0.05 for p in table["order"][1:]), table["order"]
