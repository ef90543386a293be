"""The paper's Table 1 (charged particle, T = 20, reduced (+), left rule) from Python."""

import pathlib

import pytest

import ddirac

CHARGED_PARTICLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "charged_particle.toml"
# N, the printed error ‖q(T) − q_N‖ (paper Table 1), and its significant digits.
TABLE_1 = [(10, 1.6781, 5), (50, 0.25971, 5), (100, 0.06626, 4), (200, 0.01664, 4)]


# The coarsest row, h = 2, turns theta by 2 rad a step: its runs warn under_resolved, as they should.
@pytest.mark.filterwarnings("ignore::ddirac.UnderResolvedWarning")
@pytest.mark.parametrize("steps, printed, digits", TABLE_1)
def test_table_1_from_python_equals_the_command_lines_numbers_bit_for_bit(tmp_path, steps, printed, digits):
    spec = ddirac.load(CHARGED_PARTICLE, overrides={"time.steps": steps})
    # The command line's own run, its summary.json written with round-trip numbers ...
    on_disk = spec.run(out=tmp_path / "run").summary["reference_error"]
    # ... and the arrays path, and a run from plain arguments.
    in_memory = spec.run().summary["reference_error"]
    direct = ddirac.simulate(ddirac.System.builtin("charged_particle"), q0=[0, 0, 0, 0], p0=[1, 0, 1, 1],
                             steps=steps, duration=20.0, rule="left", reduced=True).summary["reference_error"]
    assert on_disk == in_memory == direct
    assert float(f"{direct:.{digits}g}") == printed
