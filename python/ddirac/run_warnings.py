"""The warnings of runs, as Python warnings: :class:`RunWarning` and one subclass per kind.

A run that completes but that a user should look at lists its warnings in ``summary["warnings"]`` (as
``summary.json`` does: ``{kind, step, t, message, count}``). Every entry point that runs something
(:func:`ddirac.simulate`, :meth:`ddirac.Spec.run`, :func:`ddirac.ensemble`, :func:`ddirac.convergence`,
:func:`ddirac.check` for the warnings a run would have) also emits them through the :mod:`warnings`
module, one warning per kind, pointing at the user's call. Filter or escalate them as any warning::

    warnings.simplefilter("ignore", ddirac.SubdividedWarning)   # silence one kind
    warnings.simplefilter("error", ddirac.RunWarning)           # a warned run raises instead

A kind this version does not know is emitted as a plain :class:`RunWarning`, never dropped.
"""

import math
import os
import sys
import warnings
from types import FrameType
from typing import Any, Iterable, Mapping, Optional, Sequence


class RunWarning(UserWarning):
    """A run completed, but with something a user should look at: the base class of ddirac's warnings.

    ``kind`` is the kind as ``summary.json`` names it; ``step`` and ``t`` those of the first event (None
    for a finding before the first step, or for an ensemble); ``count`` the number of events (of one
    run), or of members that had the kind (of an ensemble); ``text`` the summary's message (None for an
    ensemble, whose members' messages differ); ``members`` the ensemble's size (None for one run);
    ``step_sizes`` the step sizes h of a convergence study's runs that had the kind (None otherwise).
    """

    def __init__(self, message: str, kind: Optional[str] = None, step: Optional[int] = None,
                 t: Optional[float] = None, count: Optional[int] = None, text: Optional[str] = None,
                 members: Optional[int] = None, step_sizes: Optional[Sequence[float]] = None) -> None:
        super().__init__(message)
        self.kind = kind
        self.step = step
        self.t = t
        self.count = count
        self.text = text
        self.members = members
        self.step_sizes = None if step_sizes is None else list(step_sizes)


class NotInvariantWarning(RunWarning):
    """``not_invariant``: a reduced run with ``check_invariance`` off of an L_d that fails the invariance
    check; the reduced equations hold μ constant although the true momentum map is not conserved."""


class InvarianceUndecidedWarning(RunWarning):
    """``invariance_undecided``: the same, when the invariance of L_d could not be tested."""


class EnergyJumpWarning(RunWarning):
    """``energy_jump``: the energy of a step jumped and did not come back (a singular potential stepped
    over, Newton's method converged to another root)."""


class NewtonFallbackWarning(RunWarning):
    """``newton_fallback``: the closed-form step failed its residual test and Newton's method solved it."""


class UnderResolvedWarning(RunWarning):
    """``under_resolved``: an angle turned by more than 1 rad in one step where the Legendre map is
    regular, or a rigid body turned by more than 1 rad in one step: the step does not resolve the
    motion."""


class SingularChartWarning(RunWarning):
    """``singular_chart``: an angle's advance in one step was not resolved (more than 1 rad, or its
    rate changed by more than half within the step at several times its typical advance) where the
    Legendre map has become near-singular: the coordinates are singular nearby (a pole of spherical
    coordinates, the upright attitude in Euler angles, say)."""


class EnergyDriftWarning(RunWarning):
    """``energy_drift``: the energy moved away from its first step's value by more than 10 % of its scale
    without a jump."""


class SubdividedWarning(RunWarning):
    """``subdivided``: a step failed or converged implausibly and was taken again as equal sub-steps."""


class LooseToleranceWarning(RunWarning):
    """``loose_tolerance``: the Newton tolerance lets each step err by more than the step's own
    truncation error; the result may be no more accurate than the tolerance allows."""


class NoEnergyWarning(RunWarning):
    """``no_energy``: a rigid body whose Lagrangian is degenerate in its velocities at the initial data:
    the energy is not reported (NaN); the motion itself is computed."""


class SensitivityLostWarning(RunWarning):
    """``sensitivity_lost``: with ``sensitivities=True``, the tangent map could not be carried through a
    step (its linearized equations are singular there) or a chart switch; ``run.sensitivity`` is not finite."""


#: The class of each kind, by the name ``summary.json`` gives it.
KINDS: dict[str, type[RunWarning]] = {
    "not_invariant": NotInvariantWarning,
    "invariance_undecided": InvarianceUndecidedWarning,
    "energy_jump": EnergyJumpWarning,
    "newton_fallback": NewtonFallbackWarning,
    "under_resolved": UnderResolvedWarning,
    "singular_chart": SingularChartWarning,
    "energy_drift": EnergyDriftWarning,
    "subdivided": SubdividedWarning,
    "loose_tolerance": LooseToleranceWarning,
    "no_energy": NoEnergyWarning,
    "sensitivity_lost": SensitivityLostWarning,
}

# The package's directory: frames of files in it are skipped, so that a warning points at the user's call.
_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warning_class(kind: str) -> type[RunWarning]:
    """The class of the warning kind ``kind``; :class:`RunWarning` for a kind this version does not know."""
    return KINDS.get(kind, RunWarning)


def warn_run(entries: Iterable[Mapping[str, Any]], what: str = "the run warned") -> None:
    """Emits the warnings of one run, ``summary["warnings"]`` (or a check's verdict): one per entry,
    saying ``what`` and the kind, the step and time of the first event, the number of events and the
    message."""
    for entry in entries:
        kind = str(entry.get("kind"))
        details, fields = _first_event(entry)
        _emit(warning_class(kind)(f"{what} {kind} {details}", kind=kind, **fields))


def warn_members(counts: Mapping[str, int], members: int) -> None:
    """Emits the warnings of an ensemble of ``members`` members: one per kind, with ``counts[kind]`` the
    number of members whose run had it."""
    for kind, count in sorted(counts.items()):
        if not count:
            continue
        message = (f"{count} of {members} member{'s' if members != 1 else ''} of the ensemble warned {kind} "
                   f"(the run of one member, `ddirac.load(spec, overrides=...).run()`, says where and why)")
        _emit(warning_class(kind)(message, kind=kind, count=int(count), members=int(members)))


def warn_study(runs: Sequence[tuple[float, Sequence[Mapping[str, Any]]]]) -> dict[str, list[float]]:
    """Emits the warnings of a convergence study, whose runs are ``(step size h, summary["warnings"])``:
    one per kind, saying at which step sizes it occurred and the first event of the first such run.
    Returns those step sizes by kind."""
    kinds: dict[str, list[tuple[float, Mapping[str, Any]]]] = {}
    for h, entries in runs:
        for entry in entries:
            kinds.setdefault(str(entry.get("kind")), []).append((h, entry))
    for kind, hits in kinds.items():
        sizes = [h for h, _ in hits]
        h, first = hits[0]
        details, fields = _first_event(first)
        message = (f"the convergence study warned {kind} at step size{'s' if len(sizes) > 1 else ''} h = "
                   f"{', '.join(f'{s:.6g}' for s in sizes)}; with h = {h:.6g} {details}")
        _emit(warning_class(kind)(message, kind=kind, step_sizes=sizes, **fields))
    return {kind: [h for h, _ in hits] for kind, hits in kinds.items()}


def _first_event(entry: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """The words for one entry of ``summary["warnings"]`` — ``(first at step k, t = t_k; n events):
    message`` — and its fields as :class:`RunWarning` takes them."""
    step, t, count = entry.get("step"), entry.get("t"), int(entry.get("count") or 1)
    text = str(entry.get("message", ""))
    if step is None:
        at = "before the first step"
    else:
        at = f"first at step {step}" + ("" if t is None or not math.isfinite(t) else f", t = {t:.6g}")
    details = f"({at}; {count} event{'s' if count != 1 else ''}): {text}"
    return details, {"step": step, "t": t, "count": count, "text": text}


def _emit(warning: RunWarning) -> None:
    """Issues ``warning`` at the first frame outside the package: the user's call."""
    frame: Optional[FrameType] = sys._getframe(0)
    level = 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    warnings.warn(warning, stacklevel=level)
