"""ddirac.convergence returns a ConvergenceTable: the rows as before (a dict), what the errors are
measured against (labelled as convergence.csv labels it), and the observed order judged against the
method's declared order — the order `ddirac convergence` finds for the same spec, with a verdict."""

import csv
import pathlib
import re
import subprocess
import warnings

import pytest

import ddirac
import command_line

REPO = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def cli_convergence(tmp_path, spec, steps, sets):
    """(rows of convergence.csv, the stable order and its N range as printed) of `ddirac convergence`."""
    out = tmp_path / "cli"
    args = [command_line.built(), "convergence", str(spec), "--steps", ",".join(map(str, steps)), "--out", str(out)]
    for key, value in sets.items():
        args += ["--set", f"{key}={value}"]
    done = subprocess.run(args, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(out / "convergence.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    stable = re.search(r"stable at ([0-9.]+) over N = (\d+)…(\d+)", done.stdout)
    return rows, stable


def test_a_table_without_exact_solution_names_its_reference_run_and_judges_the_order(tmp_path):
    sets = {"time.duration": 1}
    rows, stable = cli_convergence(tmp_path, EXAMPLES / "double_spherical_pendulum.toml", [100, 200, 400], sets)
    table = ddirac.load(EXAMPLES / "double_spherical_pendulum.toml", overrides=sets).convergence([100, 200, 400])
    assert isinstance(table, ddirac.ConvergenceTable) and isinstance(table, dict)
    # Backwards compatible: the keys of the dict as before.
    assert table["steps"] == [100, 200, 400] and table["reference"] == 3200 and table["warnings"] == {}
    assert table["error"] == pytest.approx([float(r["error"]) for r in rows], rel=1e-12)
    assert table.reference_label == rows[0]["reference"] == "reference run N=3200"
    assert "reference run of the same method with N = 3200 steps" in table.against
    assert table.declared_order == 2
    assert stable and f"{table.observed_order:.2f}" == stable.group(1)
    assert table.stable_steps == (int(stable.group(2)), int(stable.group(3)))
    assert table.verdict == "as declared" and table["verdict"] == "as declared"
    assert "declared order 2" in table.message and "as declared" in table.message
    assert "as declared" in str(table)


def test_against_the_exact_solution_the_left_rule_is_judged_against_its_first_order(tmp_path):
    steps = [10, 50, 100, 200]
    rows, stable = cli_convergence(tmp_path, EXAMPLES / "charged_particle.toml", steps, {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ddirac.UnderResolvedWarning)  # h = 2 turns theta by 2 rad a step
        table = ddirac.load(EXAMPLES / "charged_particle.toml").convergence(steps)
    assert table.reference == "exact" and table.reference_label == rows[0]["reference"] == "exact solution"
    assert table.declared_order == 1  # the left rule
    assert f"{table.observed_order:.2f}" == stable.group(1)
    # This system's left-rule table (the paper's Table 1) converges at order 2: above the declared order.
    assert table.verdict == "above declared"


def test_a_composition_is_judged_against_its_order(tmp_path):
    sets = {"method.rule": "midpoint", "method.order": 4}
    rows, stable = cli_convergence(tmp_path, EXAMPLES / "charged_particle.toml", [25, 50, 100, 200], sets)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ddirac.UnderResolvedWarning)  # h = 0.8 turns theta by 1.06 rad a step
        table = ddirac.load(EXAMPLES / "charged_particle.toml", overrides=sets).convergence([25, 50, 100, 200])
    assert table.declared_order == 4 and f"{table.observed_order:.2f}" == stable.group(1)
    assert table.verdict == "as declared"


def test_one_observed_order_cannot_be_judged():
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    table = ddirac.convergence(dsp, [100, 200], duration=0.5, q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1])
    assert table.observed_order is None and table.stable_steps is None and table.verdict == "undetermined"
    assert "one observed order only" in table.message
