"""Convergence studies from Python: :func:`convergence`, as ``ddirac convergence`` tabulates them."""

import math

import numpy as np

from . import _ddirac
from .run_warnings import warn_study

#: Without an exact solution, errors are measured against a run with this many times the finest N (the
#: command line's reference): for a second-order method its own error is 1/63 of the finest row's.
REFERENCE_FACTOR = 8


def convergence(system, steps, duration, q0, p0=None, v0=None, **run):
    """Runs ``system`` with each number of steps N in ``steps`` over ``duration`` (h = T/N) and returns
    the table: ``steps``, ``step``, ``error`` (‖q_N − q(T)‖ against the exact solution when the system
    has one, else against a run of the same method with 8 times the finest N, angle differences
    wrapped to (−π, π]), ``order`` (observed between consecutive rows, p = ln(e_i/e_{i+1}) /
    ln(h_i/h_{i+1}); None for the first) and ``reference`` (``"exact"`` or the reference run's N).
    Other keywords are those of :func:`ddirac.simulate`.

    The runs' warnings are emitted once per kind as :class:`ddirac.RunWarning` subclasses, saying at
    which step sizes they occurred (the reference run's included); ``warnings`` in the table maps each
    kind to those step sizes."""
    from .run import _simulate

    counts = sorted({int(n) for n in steps})
    if not counts or counts[0] < 1:
        raise _ddirac.Error("`steps` must list at least one number of steps, each at least 1")
    if "step" in run or "every" in run:
        raise _ddirac.Error("a convergence study sets `step` and `every` itself; give `steps` and `duration`")

    warned = []

    def final(n):
        result = _simulate(system, q0, p0=p0, v0=v0, steps=n, duration=duration, every=n, **run)
        if result.summary["warnings"]:
            warned.append((duration / n, result.summary["warnings"]))
        return result.q[-1], result.summary["reference_error"]

    finals = [final(n) for n in counts]
    if all(error is not None for _, error in finals):
        errors, reference = [error for _, error in finals], "exact"
    else:
        n_ref = REFERENCE_FACTOR * counts[-1]
        q_ref, _ = final(n_ref)
        angles = np.array([name in system.angles for name in system.coordinates])
        errors = []
        for q, _ in finals:
            d = q - q_ref
            d[angles] = (d[angles] + math.pi) % (2 * math.pi) - math.pi
            errors.append(float(np.linalg.norm(d)))
        reference = n_ref
    h = [duration / n for n in counts]
    orders = [None] + [
        math.log(errors[i] / errors[i + 1]) / math.log(h[i] / h[i + 1]) if errors[i] > 0 and errors[i + 1] > 0 else None
        for i in range(len(counts) - 1)
    ]
    kinds = warn_study(warned)
    return {"steps": counts, "step": h, "error": errors, "order": orders, "reference": reference, "warnings": kinds}
