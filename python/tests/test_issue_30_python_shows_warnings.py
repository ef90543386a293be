"""A run's warnings reach Python through the `warnings` module, as subclasses of ddirac.RunWarning (one
per kind), from every entry point that runs something: simulate, Spec.run, ensemble (one warning per kind
with the number of members that had it), convergence (one per kind, with the step sizes) and check. They
point at the user's call, stay in run.summary["warnings"], and `simplefilter("error", ddirac.RunWarning)`
turns a warned run into an exception.

The case of the issue: Kepler falling straight in (zero angular momentum) reaches the singularity at
r = 0, where the energy jumps and steps are subdivided; Python used to say nothing."""

import pathlib
import warnings

import numpy as np
import pytest

import ddirac
from ddirac.run_warnings import KINDS, warn_run

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
KEPLER = EXAMPLES / "kepler.toml"

# From r = 1 at rest the body falls into the centre at t = π/(2√2) ≈ 1.11 and, stepped over the
# singularity, comes out on the other side with a far higher energy.
STEP, DURATION = 0.01, 2.0
FALLING = {"initial.p.phi": 0.0, "initial.p.r": 0.0, "time.step": STEP, "time.duration": DURATION,
           "output.every": 1}


def _falling_straight_in():
    kepler = ddirac.System.builtin("kepler")
    return ddirac.simulate(kepler, q0=[1.0, 0.0], p0=[0.0, 0.0], step=STEP, duration=DURATION, reduced=True)


def _ours(record):
    """The RunWarnings among the recorded warnings."""
    return [w for w in record if issubclass(w.category, ddirac.RunWarning)]


def test_every_kind_has_its_class_exported_under_run_warning():
    assert issubclass(ddirac.RunWarning, UserWarning)
    for kind, cls in KINDS.items():
        name = "".join(part.capitalize() for part in kind.split("_")) + "Warning"
        assert getattr(ddirac, name) is cls and name in ddirac.__all__
        assert issubclass(cls, ddirac.RunWarning) and cls is not ddirac.RunWarning
    assert "RunWarning" in ddirac.__all__
    assert set(KINDS) == {"not_invariant", "invariance_undecided", "energy_jump", "newton_fallback", "under_resolved",
                          "singular_chart", "energy_drift", "subdivided", "loose_tolerance", "no_energy",
                          "sensitivity_lost"}


def test_kepler_falling_straight_in_warns_in_python_at_the_callers_line():
    with pytest.warns(ddirac.RunWarning) as record:
        run = _falling_straight_in()
    ours = _ours(record)
    # The summary keeps its warnings, as before, and each is emitted once with its own class.
    assert run.energy[0] == -1.0 and run.energy.max() > 1000.0  # the energy jumps at r = 0
    kinds = [w["kind"] for w in run.summary["warnings"]]
    assert "energy_jump" in kinds and "subdivided" in kinds
    assert [type(w.message) for w in ours] == [KINDS[k] for k in kinds]
    for w, entry in zip(ours, run.summary["warnings"]):
        text = str(w.message)
        assert entry["kind"] in text and entry["message"] in text
        assert f"step {entry['step']}" in text and f"{entry['count']} event" in text
        assert (w.message.kind, w.message.step, w.message.count) == (entry["kind"], entry["step"], entry["count"])
        assert w.filename == __file__  # the user's line, not the package's
    assert any(issubclass(w.category, ddirac.EnergyJumpWarning) for w in ours)
    assert any(issubclass(w.category, ddirac.SubdividedWarning) for w in ours)


@pytest.mark.parametrize("cls, pattern", [
    (ddirac.EnergyJumpWarning, r"energy_jump \(first at step \d+, t = 1\.\d+; 1 event\): the energy jumped"),
    (ddirac.SubdividedWarning, r"subdivided \(first at step \d+, t = 1\.\d+; \d+ events\): a step failed"),
    (ddirac.SingularChartWarning, r"singular_chart \(first at step \d+, t = 1\.\d+; \d+ events\)"),
])
def test_each_kind_of_the_fall_is_its_own_class(cls, pattern):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ddirac.RunWarning)  # the other kinds
        with pytest.warns(cls, match=pattern):
            _falling_straight_in()


def test_escalating_run_warnings_makes_a_warned_run_an_error_and_a_clean_run_passes():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ddirac.RunWarning)
        with pytest.raises(ddirac.RunWarning):
            _falling_straight_in()
        # The double spherical pendulum of the example, with its own step, has no warning.
        clean = ddirac.load(EXAMPLES / "double_spherical_pendulum.toml", overrides={"time.duration": 10.0}).run()
    assert clean.summary["warnings"] == []


def test_one_kind_can_be_silenced_and_the_others_still_show():
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", ddirac.SubdividedWarning)
        _falling_straight_in()
    shown = {type(w.message) for w in _ours(record)}
    assert ddirac.EnergyJumpWarning in shown and ddirac.SubdividedWarning not in shown


def test_an_unknown_kind_is_a_plain_run_warning_not_dropped():
    entry = {"kind": "brand_new_kind", "step": 7, "t": 0.07, "message": "something new happened", "count": 3}
    with pytest.warns(ddirac.RunWarning) as record:
        warn_run([entry])
    (w,) = record
    assert type(w.message) is ddirac.RunWarning and w.message.kind == "brand_new_kind"
    assert "brand_new_kind" in str(w.message) and "something new happened" in str(w.message)
    assert w.filename == __file__


def test_a_spec_run_warns_in_memory_and_with_files(tmp_path):
    spec = ddirac.load(KEPLER, overrides=FALLING)
    for run in (spec.run, lambda: spec.run(out=tmp_path / "out")):
        with pytest.warns(ddirac.RunWarning) as record:
            result = run()
        kinds = [w["kind"] for w in result.summary["warnings"]]
        assert "energy_jump" in kinds and [type(w.message) for w in record] == [KINDS[k] for k in kinds]
        assert all(w.filename == __file__ for w in record)


def test_an_ensemble_warns_once_per_kind_with_the_number_of_members_that_had_it():
    spec = ddirac.load(KEPLER, overrides=FALLING)
    # Members 0 and 2 fall straight in; 1 and 3 keep the example's angular momentum and orbit.
    members = {"initial.p.phi": np.array([0.0, 0.8, 0.0, 0.8])}
    with pytest.warns(ddirac.RunWarning) as record:
        result = ddirac.ensemble(spec, members=members, threads=2)
    jumps = [w for w in record if w.category is ddirac.EnergyJumpWarning]
    assert len(jumps) == 1 and jumps[0].filename == __file__
    assert jumps[0].message.count == 2 and jumps[0].message.members == 4
    assert "2 of 4 members" in str(jumps[0].message)
    assert result.warnings["energy_jump"] == 2
    kinds = [type(w.message) for w in _ours(record)]
    assert len(kinds) == len(set(kinds)) == len(result.warnings)


def test_a_convergence_study_warns_once_per_kind_with_its_step_sizes():
    kepler = ddirac.System.builtin("kepler")
    # h = 0.01 and 0.005 step over the singularity, and so does the reference run (h = 0.000625).
    with pytest.warns(ddirac.RunWarning) as record:
        table = ddirac.convergence(kepler, [200, 400], duration=DURATION, q0=[1.0, 0.0], p0=[0.0, 0.0], reduced=True)
    ours = _ours(record)
    kinds = [type(w.message) for w in ours]
    assert len(kinds) == len(set(kinds)) == len(table["warnings"])
    (jump,) = [w for w in ours if w.category is ddirac.EnergyJumpWarning]
    assert jump.filename == __file__
    assert jump.message.step_sizes == table["warnings"]["energy_jump"]
    assert jump.message.step_sizes == [DURATION / 200, DURATION / 400, DURATION / 3200]
    assert "h = 0.01, 0.005, 0.000625" in str(jump.message)


def test_check_emits_the_warnings_a_run_would_have():
    pendulum = ddirac.System(lagrangian="0.5*theta_dot^2 + cos(theta)", group=["theta"], angles=["theta"])
    with pytest.warns(ddirac.RunWarning) as record:
        report = ddirac.check(pendulum, q0=[1.0], p0=[0.0], step=0.01, steps=10, reduced=True,
                              check_invariance=False)
    (w,) = _ours(record)
    assert w.category is ddirac.NotInvariantWarning
    (entry,) = report["verdict"]["warnings"]
    assert entry["kind"] == "not_invariant" and entry["message"] in str(w.message)
    assert "before the first step" in str(w.message) and w.filename == __file__


def test_the_readme_snippet_that_filters_and_escalates_runs_as_written():
    readme = (pathlib.Path(__file__).resolve().parents[2] / "README.md").read_text()
    after = readme.split("Filter or escalate them as any warning:", 1)[1]
    snippet = after.split("```python\n", 1)[1].split("```", 1)[0]
    with warnings.catch_warnings():
        exec(snippet, {"ddirac": ddirac})
        # Escalated: a warned run raises; the silenced kind alone would not.
        with pytest.raises(ddirac.RunWarning):
            _falling_straight_in()
