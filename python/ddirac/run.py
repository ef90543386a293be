"""One run: :func:`simulate` and the :class:`Run` it returns."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence, Union, overload

import numpy as np

from . import _ddirac
from .progress import ProgressArgument
from .run_warnings import warn_run
from .system import System

if TYPE_CHECKING:  # optional: imported by the methods that need them
    import pandas
    import xarray

    from .rigid import RigidBody, RigidRun

#: Initial data: a sequence in the order of ``system.coordinates``, or a mapping by coordinate (a name,
#: a SymPy symbol or dynamicsymbol; for velocities also the derivative ``q(t).diff(t)``).
Vector = Union[Sequence[float], "np.ndarray", Mapping[Any, float]]

class Run:
    """The rows of a run as NumPy arrays, and its summary.

    Attributes: ``t`` (rows,), ``q`` and ``p`` (rows, n), ``energy`` (the Hamiltonian H(q, p)),
    ``discrete_energy`` (L_d(q_k, q_{k+1}), NaN on the last row), ``momentum_map`` (rows, number of
    group coordinates), ``chart`` (rows: the chart of the system's atlas each row's step was in, 0 for
    the main chart, in which ``q`` and ``p`` are given; None when the run cannot switch charts: a system
    without an atlas, or ``atlas=False``), ``summary`` (the dict ``summary.json`` holds),
    ``coordinates`` (the names of the columns of ``q`` and ``p``), ``group`` (those of
    ``momentum_map``) and ``sensitivity`` (with ``sensitivities=True``: the tangent map
    d(q_N, p_N)/d(q_0, p_0), shape (2n, 2n), rows and columns q then p in the order of ``coordinates``;
    else None).
    """

    t: np.ndarray
    q: np.ndarray
    p: np.ndarray
    energy: np.ndarray
    discrete_energy: np.ndarray
    momentum_map: np.ndarray
    chart: Optional[np.ndarray]
    summary: dict[str, Any]
    coordinates: list[str]
    group: list[str]
    sensitivity: Optional[np.ndarray]

    def __init__(self, arrays: Mapping[str, Any], coordinates: Sequence[str], group: Sequence[str]) -> None:
        self.t = arrays["t"]
        self.q = arrays["q"]
        self.p = arrays["p"]
        self.energy = arrays["energy"]
        self.discrete_energy = arrays["discrete_energy"]
        self.momentum_map = arrays["momentum_map"]
        self.chart = arrays["chart"] if arrays.get("switching") else None
        self.summary = arrays["summary"]
        self.coordinates = list(coordinates)
        self.group = list(group)
        tangent = self.summary.get("sensitivity")
        self.sensitivity = None if tangent is None else np.array(tangent["state"], dtype=float)

    def __len__(self) -> int:
        return len(self.t)

    def __repr__(self) -> str:
        return (f"ddirac.Run({self.summary['system']!r}, rows={len(self)}, steps={self.summary['steps']}, "
                f"step={self.summary['step']})")

    def columns(self) -> dict[str, np.ndarray]:
        """The rows as named columns, as ``trajectory.csv`` names them: ``t``, each coordinate,
        ``p_<coordinate>``, ``energy``, ``discrete_energy``, ``momentum_<group coordinate>``, and
        ``chart`` when the run can switch charts of an atlas (as ``trajectory.csv`` has it then)."""
        out = {"t": self.t}
        out.update({name: self.q[:, i] for i, name in enumerate(self.coordinates)})
        out.update({f"p_{name}": self.p[:, i] for i, name in enumerate(self.coordinates)})
        out["energy"] = self.energy
        out["discrete_energy"] = self.discrete_energy
        out.update({f"momentum_{name}": self.momentum_map[:, i] for i, name in enumerate(self.group)})
        if self.chart is not None:
            out["chart"] = self.chart
        return out

    def to_xarray(self) -> xarray.Dataset:
        """The run as an ``xarray.Dataset`` over ``t`` (xarray is imported only here): ``q`` and ``p`` with a
        ``coordinate`` dimension, ``momentum_map`` with a ``group`` dimension, ``energy``,
        ``discrete_energy``, and ``chart`` when the run can switch charts; the summary in
        ``attrs["summary"]``."""
        import xarray

        variables: dict[str, Any] = {
            "q": (("t", "coordinate"), self.q),
            "p": (("t", "coordinate"), self.p),
            "energy": ("t", self.energy),
            "discrete_energy": ("t", self.discrete_energy),
            "momentum_map": (("t", "group"), self.momentum_map),
        }
        if self.chart is not None:
            variables["chart"] = ("t", self.chart)
        return xarray.Dataset(
            variables,
            coords={"t": self.t, "coordinate": self.coordinates, "group": self.group},
            attrs={"summary": self.summary},
        )

    def to_pandas(self) -> pandas.DataFrame:
        """The named columns as a ``pandas.DataFrame`` (pandas is imported only here)."""
        import pandas

        return pandas.DataFrame(self.columns())


@overload
def simulate(system: RigidBody, q0: Optional[Vector] = None, p0: Optional[Vector] = None, v0: Optional[Vector] = None,
             step: Optional[float] = None, steps: Optional[int] = None, duration: Optional[float] = None,
             rule: str = "midpoint", variant: str = "plus", reduced: bool = False, every: int = 1,
             wrap_angles: bool = False, progress: ProgressArgument = None, *, R0: Any,
             Pi0: Optional[Sequence[float]] = None, Omega0: Optional[Sequence[float]] = None,
             **method: Any) -> RigidRun: ...


@overload
def simulate(system: System, q0: Optional[Vector] = None, p0: Optional[Vector] = None, v0: Optional[Vector] = None,
             step: Optional[float] = None, steps: Optional[int] = None, duration: Optional[float] = None,
             rule: str = "midpoint", variant: str = "plus", reduced: bool = False, every: int = 1,
             wrap_angles: bool = False, progress: ProgressArgument = None, *, R0: Any = None,
             Pi0: Optional[Sequence[float]] = None, Omega0: Optional[Sequence[float]] = None,
             **method: Any) -> Run: ...


def simulate(system: System, q0: Optional[Vector] = None, p0: Optional[Vector] = None, v0: Optional[Vector] = None,
             step: Optional[float] = None, steps: Optional[int] = None, duration: Optional[float] = None,
             rule: str = "midpoint", variant: str = "plus", reduced: bool = False, every: int = 1,
             wrap_angles: bool = False, progress: ProgressArgument = None, *, R0: Any = None,
             Pi0: Optional[Sequence[float]] = None, Omega0: Optional[Sequence[float]] = None,
             **method: Any) -> Run:
    """Integrates ``system`` from ``q0`` with momenta ``p0`` or velocities ``v0``.

    Give two of ``step``, ``steps`` and ``duration`` (all three must agree). ``q0``, ``p0`` and
    ``v0`` are sequences in the order of ``system.coordinates``, or dicts by coordinate (its name, or a
    SymPy symbol or dynamicsymbol ``q(t)`` of that name; the keys of ``v0`` may be ``q(t).diff(t)``).
    ``rule`` is ``left``, ``right``, ``midpoint`` or ``trapezoid``; ``variant`` ``plus`` or ``minus``;
    ``reduced=True`` integrates the reduced equations and reconstructs the group motion. The other
    method keys are those of a spec's ``[method]`` table, with the same defaults and checked by the same
    rules (a refusal says the same as ``ddirac run`` does): ``connection`` (rows of K, one per group
    coordinate), ``tolerance``, ``max_iterations``, ``jacobian`` (``reuse``: chord Newton, or ``fresh``;
    ``reuse_jacobian=True``/``False`` says the same), ``derivatives`` (``auto``, ``compiled``, ``dual``),
    ``check_invariance``,
    ``on_energy_jump`` (``warn``, ``error``, ``ignore``), ``energy_jump_threshold``, ``order`` (2, 4,
    6 or 8: orders above 2 compose the basic step of a symmetric rule, midpoint or trapezoid) and
    ``composition`` (its coefficient set: ``suzuki``, ``kahan-li`` or ``triple-jump``) and ``atlas``
    (``False`` keeps every step in the main chart of a system with an atlas of charts) and
    ``sensitivities`` (``True`` propagates the tangent map d(q_N, p_N)/d(q_0, p_0) through every step
    by the implicit function theorem: :attr:`Run.sensitivity`). Every
    ``every``-th row is kept (and the last).

    The GIL is released while the run integrates; Ctrl-C stops it with ``KeyboardInterrupt``.
    ``progress`` shows a bar (``True``; by default only in a notebook), or is called as
    ``progress(k, steps)`` about ten times a second, and with ``k = steps`` when the run completes.

    The run's warnings (``summary["warnings"]``) are also emitted as :class:`ddirac.RunWarning`
    subclasses, one per kind (``warnings.simplefilter("error", ddirac.RunWarning)`` makes them errors).

    A rigid body (``System.builtin("rigid_body", ...)``, a :class:`ddirac.RigidBody`) starts from the
    attitude ``R0`` (3 × 3, body to space: a rotation to 1e-12) with the body angular momentum ``Pi0``
    or the body angular velocity ``Omega0`` (and its shape coordinates, if any, from ``q0`` with ``p0``
    beside ``Pi0`` or ``v0`` beside ``Omega0``), and returns a :class:`ddirac.RigidRun` (``run.R`` of shape
    (rows, 3, 3), ``run.Pi`` (rows, 3)); ``reduced=True`` runs the reduced equations of a body invariant
    under every rotation (a heavy body is refused). ``variant``, ``connection``, ``atlas`` and
    ``wrap_angles`` have no meaning on SO(3).
    """
    from .rigid import RigidBody, simulate_rigid

    if isinstance(system, RigidBody):
        if wrap_angles:
            raise _ddirac.Error("`wrap_angles` has no meaning for a rigid body: its attitude is the matrix R")
        keys = _method_keys(rule, variant, reduced, method)
        result: Run = simulate_rigid(system, R0, Pi0, Omega0, q0, p0, v0, step, steps, duration, every, keys,
                                     progress)
    else:
        if R0 is not None or Pi0 is not None or Omega0 is not None:
            raise _ddirac.Error(f"`R0`, `Pi0` and `Omega0` are the initial data of a rigid body; "
                                f"{system.name!r} has coordinates: give `q0` and one of `p0`, `v0`")
        if q0 is None:
            raise _ddirac.Error("`q0` is missing: the initial configuration, one number per coordinate "
                                f"({', '.join(system.coordinates)}), or a dict by coordinate")
        result = _simulate(system, q0, p0, v0, step, steps, duration, rule, variant, reduced, every, wrap_angles,
                           progress, **method)
    warn_run(result.summary["warnings"])
    return result


def _simulate(system: System, q0: Vector, p0: Optional[Vector] = None, v0: Optional[Vector] = None,
              step: Optional[float] = None, steps: Optional[int] = None, duration: Optional[float] = None,
              rule: str = "midpoint", variant: str = "plus", reduced: bool = False, every: int = 1,
              wrap_angles: bool = False, progress: ProgressArgument = None, **method: Any) -> Run:
    """:func:`simulate` without emitting the run's warnings (they are in its summary)."""
    args = _prepare(system, q0, p0, v0, step, steps, duration, rule, variant, reduced, method)
    every = _count(every, "every")
    from .progress import callback

    reporter = callback(progress, args["steps"])
    try:
        arrays = _ddirac.simulate(system._handle, args, every, bool(wrap_angles), reporter.report)
        reporter.done()
    finally:
        reporter.close()
    names = system.coordinates
    return Run(arrays, names, system.group)


def check(system: System, q0: Vector, p0: Optional[Vector] = None, v0: Optional[Vector] = None,
          step: Optional[float] = None, steps: Optional[int] = None, duration: Optional[float] = None,
          rule: str = "midpoint", variant: str = "plus", reduced: bool = False, **method: Any) -> dict[str, Any]:
    """Tests the hypotheses a run of :func:`simulate` with the same arguments would rest on, without
    integrating: the invariance of L_d under each group translation (reduced runs), the
    2π-periodicity of L in each angle, the connection's axioms, the rank of the Legendre map, the
    primary constraint and, with an atlas, each chart (``charts``: its ``name``, whether its maps are
    ``inverse`` on the ``points`` sampled over its domain, the largest ``round_trip`` and where,
    ``worst``, a point ``singular_where_good``, and its ``invariance`` and ``periodicity``). Returns
    the findings as a dict, with ``verdict``: whether such a run would
    go (``runs``), the ``error`` it would fail with, or the ``warnings`` it would run with (each
    ``{kind, step, t, message, count}``, as in a run's summary; they are also emitted as
    :class:`ddirac.RunWarning` subclasses)."""
    args = _prepare(system, q0, p0, v0, step, steps, duration, rule, variant, reduced, method)
    report = _ddirac.check(system._handle, args)
    warn_run(report["verdict"]["warnings"], what="a run with these arguments would warn")
    return report


def _prepare(system: System, q0: Vector, p0: Optional[Vector], v0: Optional[Vector], step: Optional[float],
             steps: Optional[int], duration: Optional[float], rule: str, variant: str, reduced: bool,
             method: Mapping[str, Any]) -> dict[str, Any]:
    """The arguments of a run as the dict the module takes: ``q0``, ``p0``, ``v0``, ``step``, ``steps``
    and the ``method`` keys. The module checks them by the rules a spec file's keys follow; here they
    only become plain numbers, strings and lists."""
    from .rigid import RigidBody
    from .system import System

    if not isinstance(system, System):
        raise _ddirac.Error(f"`system` must be a ddirac.System, not {type(system).__name__}")
    if isinstance(system, RigidBody):
        raise _ddirac.Error("this function does not take rigid bodies yet: `ddirac.simulate` runs them")
    keys = _method_keys(rule, variant, reduced, method)
    names = system.coordinates
    h, n = _ddirac.time_grid(None if step is None else float(step), None if steps is None else _whole(steps, "steps"),
                             None if duration is None else float(duration))
    return {"q0": _vector(q0, names, "q0"), "p0": None if p0 is None else _vector(p0, names, "p0"),
            "v0": None if v0 is None else _vector(v0, names, "v0", velocities=True), "step": h, "steps": n, "duration": None,
            "method": keys}


def _method_keys(rule: str, variant: str, reduced: bool, method: Mapping[str, Any]) -> dict[str, Any]:
    """The method keys as the module takes them: plain numbers, strings and lists, checked there by
    the rules of a spec's ``[method]`` table."""
    keys = dict(method)
    if "reuse_jacobian" in keys:  # `jacobian = "reuse"` or `"fresh"` as a boolean
        if "jacobian" in keys:
            raise _ddirac.Error("give `jacobian` or `reuse_jacobian`, not both")
        reuse = keys.pop("reuse_jacobian")
        keys["jacobian"] = None if reuse is None else ("reuse" if bool(reuse) else "fresh")
    known = _ddirac.method_keys()
    unknown = sorted(set(keys) - set(known))
    if unknown:
        raise _ddirac.Error(f"unknown method key {unknown[0]!r}; the method keys are: {', '.join(known)}")
    keys.update(rule=str(rule), variant=str(variant), reduced=bool(reduced))
    for key in ("max_iterations", "order"):
        if keys.get(key) is not None:
            keys[key] = _whole(keys[key], key)
    if keys.get("connection") is not None:
        keys["connection"] = np.atleast_2d(np.asarray(keys["connection"], dtype=float)).tolist()
    return keys


def _vector(values: Vector, names: list[str], what: str, velocities: bool = False) -> Any:
    """``values`` as the module takes them: a list in the order of ``names``, or a list of (name, value)
    pairs for a mapping by coordinate (a name, a SymPy symbol or dynamicsymbol; with ``velocities``
    also its time derivative). The module checks the entries against the coordinates."""
    if isinstance(values, Mapping):
        from .system import _coordinate_key

        return [(_coordinate_key(key, f"a key of `{what}`", velocity=velocities)[0], float(value))
                for key, value in values.items()]
    array = np.asarray(values, dtype=float)
    if array.ndim != 1:
        raise _ddirac.Error(f"`{what}` must be a sequence of numbers, one per coordinate ({', '.join(names)}), "
                            f"or a dict by coordinate; it has the shape {array.shape}")
    return array.tolist()


def _whole(value: Any, what: str) -> int:
    """``value`` as an integer, if it is a whole number (the module checks its range)."""
    if isinstance(value, bool) or not float(value).is_integer():
        raise _ddirac.Error(f"`{what}` must be a whole number, not {value!r}")
    return int(value)


def _count(value: Any, what: str) -> int:
    if isinstance(value, bool) or int(value) != value or int(value) < 1:
        raise _ddirac.Error(f"`{what}` must be a whole number of at least 1, not {value!r}")
    return int(value)
