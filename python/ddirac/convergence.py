"""Convergence studies from Python: :func:`convergence`, as ``ddirac convergence`` tabulates them."""

from __future__ import annotations

import math
from typing import Any, Optional, Sequence, Union

import numpy as np

from . import _ddirac
from .run import Run, Vector
from .run_warnings import warn_study
from .system import System

#: Without an exact solution, errors are measured against a run with this many times the finest N (the
#: command line's reference): for a second-order method its own error is 1/63 of the finest row's.
REFERENCE_FACTOR = 8

#: Consecutive observed orders are stable when they differ by at most this fraction of the larger (as
#: ``ddirac convergence`` judges them); a stable order within this fraction of the declared order is
#: the declared order.
STABLE: float = _ddirac.STABLE

#: The verdicts of :attr:`ConvergenceTable.verdict`.
VERDICTS = ("as declared", "above declared", "below declared", "undetermined")


def declared_order(rule: str = "midpoint", order: Optional[int] = 2) -> int:
    """The order the method is built to have: that of a composition (``order`` 4, 6 or 8), else 2 for
    the symmetric rules (midpoint, trapezoid) and 1 for the left and right rules."""
    if order is not None and int(order) > 2:
        return int(order)
    return 1 if str(rule) in ("left", "right") else 2


class ConvergenceTable(dict):  # type: ignore[type-arg]
    """The table of a convergence study, with its verdict on the order. A dict (the keys below), whose
    entries are also attributes:

    - ``steps`` (the numbers of steps N), ``step`` (h = T/N), ``error`` (of the final configuration),
      ``order`` (observed between consecutive rows; None for the first): the rows;
    - ``reference``: ``"exact"`` when the errors are against the system's exact solution, else the
      number of steps of the reference run they are measured against; ``reference_label`` says the
      same as ``convergence.csv``'s ``reference`` column (``exact solution`` or ``reference run
      N=6400``), ``against`` in a sentence;
    - ``declared_order``: the order the method is built to have (see :func:`declared_order`);
    - ``observed_order``: the mean observed order over the finest stretch of rows where consecutive
      observed orders agree within 10 % (as ``ddirac convergence`` finds it), or None when there is
      none; ``stable_steps``: the first and last N of that stretch;
    - ``verdict``: ``"as declared"`` (the observed order is within 10 % of the declared one), ``"above
      declared"``, ``"below declared"`` or ``"undetermined"`` (no stable observed order);
      ``message`` says it in a sentence;
    - ``warnings``: each warning kind of the runs → the step sizes h whose runs had it.

    ``str(table)`` is the table as ``ddirac convergence`` prints it."""

    @property
    def steps(self) -> list[int]:
        return self["steps"]  # type: ignore[no-any-return]

    @property
    def step(self) -> list[float]:
        return self["step"]  # type: ignore[no-any-return]

    @property
    def error(self) -> list[float]:
        return self["error"]  # type: ignore[no-any-return]

    @property
    def order(self) -> list[Optional[float]]:
        return self["order"]  # type: ignore[no-any-return]

    @property
    def reference(self) -> Union[str, int]:
        return self["reference"]  # type: ignore[no-any-return]

    @property
    def reference_label(self) -> str:
        return self["reference_label"]  # type: ignore[no-any-return]

    @property
    def against(self) -> str:
        return self["against"]  # type: ignore[no-any-return]

    @property
    def declared_order(self) -> int:
        return self["declared_order"]  # type: ignore[no-any-return]

    @property
    def observed_order(self) -> Optional[float]:
        return self["observed_order"]  # type: ignore[no-any-return]

    @property
    def stable_steps(self) -> Optional[tuple[int, int]]:
        return self["stable_steps"]  # type: ignore[no-any-return]

    @property
    def verdict(self) -> str:
        return self["verdict"]  # type: ignore[no-any-return]

    @property
    def message(self) -> str:
        return self["message"]  # type: ignore[no-any-return]

    @property
    def warnings(self) -> dict[str, list[float]]:
        return self["warnings"]  # type: ignore[no-any-return]

    def __str__(self) -> str:
        lines = [f"convergence, error {self.against}",
                 f"  {'N':>8}  {'h':>12}  {'error':>12}  {'order':>6}"]
        for n, h, e, p in zip(self.steps, self.step, self.error, self.order):
            lines.append(f"  {n:>8}  {h:>12.6g}  {e:>12.5g}  {'' if p is None else f'{p:.2f}':>6}")
        lines.append(f"  order      {self.message}")
        return "\n".join(lines)


def stability(orders: Sequence[Optional[float]]) -> Optional[tuple[int, int, float]]:
    """The finest stretch of rows whose consecutive observed orders agree within :data:`STABLE`: its
    first and last row and the mean of its observed orders; None when there is none. The rule of
    ``ddirac convergence``, from the same code."""
    return _ddirac.convergence_stability([None if p is None else float(p) for p in orders])


def _verdict(steps: list[int], orders: list[Optional[float]], declared: int, method: str) -> tuple[
        Optional[float], Optional[tuple[int, int]], str, str]:
    """(observed order, stable N range, verdict, message) of a table's observed orders."""
    found = stability(orders)
    observed = [f"{p:.2f}" for p in orders if p is not None]
    if found is None:
        why = ("one observed order only (" + observed[0] + "): whether it is stable cannot be judged"
               if len(observed) == 1 else "no observed order: give at least two numbers of steps"
               if not observed else f"not stable: no two consecutive observed orders ({', '.join(observed)}) agree "
               f"within {100 * STABLE:.0f} %; the runs may be outside the asymptotic range")
        return None, None, "undetermined", f"{why}; the declared order of {method} is {declared}"
    first, last, p = found
    if _ddirac.orders_agree(p, float(declared)):
        verdict = "as declared"
    elif p > declared:
        verdict = "above declared"
    else:
        verdict = "below declared"
    message = (f"observed order {p:.2f}, stable over N = {steps[first]}…{steps[last]} (consecutive observed orders "
               f"within {100 * STABLE:.0f} %), against the declared order {declared} of {method}: {verdict}")
    return p, (steps[first], steps[last]), verdict, message


def convergence(system: System, steps: Sequence[int], duration: float, q0: Optional[Vector] = None,
                p0: Optional[Vector] = None, v0: Optional[Vector] = None, **run: Any) -> ConvergenceTable:
    """Runs ``system`` with each number of steps N in ``steps`` over ``duration`` (h = T/N) and returns
    the table (a :class:`ConvergenceTable`, a dict): ``steps``, ``step``, ``error`` (‖q_N − q(T)‖
    against the exact solution when the system has one, else against a run of the same method with 8
    times the finest N, angle differences wrapped to (−π, π]), ``order`` (observed between
    consecutive rows, p = ln(e_i/e_{i+1}) / ln(h_i/h_{i+1}); None for the first), ``reference``
    (``"exact"`` or the reference run's N, with ``reference_label`` and ``against`` saying which) and
    the verdict on the order: ``declared_order``, ``observed_order`` (where stable), ``stable_steps``,
    ``verdict`` and ``message``. Other keywords are those of :func:`ddirac.simulate`.

    A :class:`ddirac.RigidBody` takes its initial data as :func:`ddirac.simulate` does (``R0`` with
    ``Pi0`` or ``Omega0``, and ``q0`` for its shape coordinates, if any); its error is that of the final
    configuration (R_N, s_N): the Frobenius distance of the attitudes together with the shapes'.

    The runs' warnings are emitted once per kind as :class:`ddirac.RunWarning` subclasses, saying at
    which step sizes they occurred (the reference run's included); ``warnings`` in the table maps each
    kind to those step sizes."""
    from .rigid import RigidBody, RigidRun, simulate_rigid
    from .run import _method_keys, _simulate

    counts = sorted({int(n) for n in steps})
    if not counts or counts[0] < 1:
        raise _ddirac.Error("`steps` must list at least one number of steps, each at least 1")
    if "step" in run or "every" in run:
        raise _ddirac.Error("a convergence study sets `step` and `every` itself; give `steps` and `duration`")

    warned: list[tuple[float, Any]] = []

    body = system if isinstance(system, RigidBody) else None
    rigid = body is not None
    if body is not None:
        attitude = {key: run.pop(key, None) for key in ("R0", "Pi0", "Omega0")}
        keys = _method_keys(run.pop("rule", "midpoint"), run.pop("variant", "plus"), run.pop("reduced", False), run)
        run_rule, run_order = keys["rule"], keys.get("order") or 2
    elif q0 is None:
        raise _ddirac.Error("`q0` is missing: the initial configuration, one number per coordinate "
                            f"({', '.join(system.coordinates)}), or a dict by coordinate")

    def final(n: int) -> tuple[np.ndarray, Optional[float]]:
        result: Run
        if body is not None:
            result = simulate_rigid(body, attitude["R0"], attitude["Pi0"], attitude["Omega0"], q0, p0, v0, None, n,
                                    duration, n, keys, None)
        else:
            assert q0 is not None  # refused above
            result = _simulate(system, q0, p0=p0, v0=v0, steps=n, duration=duration, every=n, **run)
        if result.summary["warnings"]:
            warned.append((duration / n, result.summary["warnings"]))
        if isinstance(result, RigidRun):
            return np.concatenate([np.asarray(result.R[-1]).ravel(), np.asarray(result.q[-1])]), None
        return result.q[-1], result.summary["reference_error"]

    finals = [final(n) for n in counts]
    reference: Union[str, int]
    if all(error is not None for _, error in finals):
        errors = [float(error) for _, error in finals if error is not None]
        reference, label, against = "exact", "exact solution", "‖q_N − q(T)‖ against the exact solution"
    else:
        n_ref = REFERENCE_FACTOR * counts[-1]
        q_ref, _ = final(n_ref)
        angles = np.array(([False] * 9 if rigid else []) + [name in system.angles for name in system.coordinates],
                          dtype=bool)
        errors = []
        for q, _ in finals:
            d = q - q_ref
            # Wrapping only what exceeds π keeps tiny differences exact, as the command line does.
            wrap = angles & (np.abs(d) > math.pi)
            d[wrap] = (d[wrap] + math.pi) % (2 * math.pi) - math.pi
            errors.append(float(np.linalg.norm(d)))
        reference, label = n_ref, f"reference run N={n_ref}"
        against = (f"‖q_N − q_ref‖ against a reference run of the same method with N = {n_ref} steps "
                   f"({REFERENCE_FACTOR} × the finest N)")
    h = [duration / n for n in counts]
    orders: list[Optional[float]] = [None]
    orders += [
        math.log(errors[i] / errors[i + 1]) / math.log(h[i] / h[i + 1]) if errors[i] > 0 and errors[i + 1] > 0 else None
        for i in range(len(counts) - 1)
    ]
    rule, order = (str(run_rule), run_order) if rigid else (str(run.get("rule", "midpoint")), run.get("order", 2))
    declared = declared_order(rule, order)
    method = f"rule {rule}" + (f", order {declared}" if declared > 2 else "")
    observed, stable, verdict, message = _verdict(counts, orders, declared, method)
    kinds = warn_study(warned)
    return ConvergenceTable(
        steps=counts, step=h, error=errors, order=orders, reference=reference, reference_label=label,
        against=against, declared_order=declared, observed_order=observed, stable_steps=stable, verdict=verdict,
        message=message, warnings=kinds,
    )
