"""Relative equilibria of the reduced discrete map on a momentum level (:func:`relative_equilibria`),
as ``ddirac equilibria`` finds them."""

from __future__ import annotations

import math
import warnings
from typing import Any, Mapping, NamedTuple, Optional, Sequence, Union

import numpy as np

from . import _ddirac
from .system import System

Values = Union[Sequence[float], Mapping[str, float], np.ndarray]


class RelativeEquilibrium:
    """A relative equilibrium of the reduced discrete map of a method with step h.

    ``shape`` and ``shape_momentum`` (arrays in the order of ``shape_names``), ``momentum`` (the level:
    the group coordinates' momenta, in the order of ``group_names``), ``group_velocity`` (their
    increment per unit time), ``multipliers`` (the eigenvalues of the linearized map, k × 2 as
    (re, im), by increasing angle), ``frequencies`` (their angle / h), ``stable`` (every multiplier
    on the unit circle to ``modulus_tolerance``), ``determinant`` (1 for a symplectic map),
    ``residual`` (‖Φ_h(x) − x‖∞), ``iterations`` and ``step``."""

    shape_names: list[str]
    group_names: list[str]
    shape: np.ndarray
    shape_momentum: np.ndarray
    momentum: np.ndarray
    group_velocity: np.ndarray
    multipliers: np.ndarray
    frequencies: np.ndarray
    stable: bool
    modulus_tolerance: float
    determinant: float
    residual: float
    iterations: int
    step: float

    def __init__(self, found: Mapping[str, Any]) -> None:
        self.shape_names = list(found["shape_names"])
        self.group_names = list(found["group_names"])
        self.shape = found["shape"]
        self.shape_momentum = found["shape_momentum"]
        self.momentum = found["momentum"]
        self.group_velocity = found["group_velocity"]
        self.multipliers = found["multipliers"]
        self.step = float(found["step"])
        self.frequencies = np.arctan2(self.multipliers[:, 1], self.multipliers[:, 0]) / self.step
        self.stable = bool(found["stable"])
        self.modulus_tolerance = float(found["modulus_tolerance"])
        self.determinant = float(found["determinant"])
        self.residual = float(found["residual"])
        self.iterations = int(found["iterations"])

    def __repr__(self) -> str:
        shape = ", ".join(f"{n}={v:.6g}" for n, v in zip(self.shape_names, self.shape))
        verdict = "stable" if self.stable else "unstable"
        return f"ddirac.RelativeEquilibrium({shape}, {verdict})"


def _by_name(values: Optional[Values], names: Sequence[str], what: str) -> list[float]:
    """``values`` (a sequence in the order of ``names`` or a mapping by name; None: zeros) as floats."""
    if values is None:
        return [0.0] * len(names)
    if isinstance(values, Mapping):
        unknown = [k for k in values if k not in names]
        if unknown:
            raise _ddirac.Error(f"`{what}` names {unknown[0]!r}, which is not one of {list(names)}")
        missing = [n for n in names if n not in values]
        if missing:
            raise _ddirac.Error(f"`{what}` lacks {missing[0]!r}: give one value for each of {list(names)}")
        out = [float(values[n]) for n in names]
    else:
        array = np.asarray(values, dtype=float).reshape(-1)
        if array.size != len(names):
            raise _ddirac.Error(f"`{what}` has {array.size} values, one for each of {list(names)} is needed")
        out = [float(v) for v in array]
    bad = [v for v in out if not math.isfinite(v)]
    if bad:
        raise _ddirac.Error(f"`{what}` holds {bad[0]}, which is not a finite number")
    return out


class RelativeEquilibriumFamily:
    """A family of relative equilibria continued along the momentum of one group coordinate, ``along``
    (:func:`relative_equilibrium_family`), with the fields of :class:`RelativeEquilibrium` stacked by
    member: ``values`` (the momentum of ``along``, one per member), ``shape`` and ``shape_momentum``
    (members × shape coordinates, in the order of ``shape_names``), ``momentum`` and ``group_velocity``
    (members × group coordinates), ``multipliers`` (members × k × 2, (re, im)), ``frequencies``
    (members × k), ``stable`` (one bool per member); ``members`` (the :class:`RelativeEquilibrium` of
    each), ``stability_changes`` (the consecutive values between which the stability changes),
    ``folds`` (where the momentum turns back and the family continues on another branch over the values
    already visited: :class:`Fold`, each with its ``momentum``, ``shape``, ``shape_momentum`` and
    ``next_member``, the index of the first member past it) and ``ended`` (``None``, or the value whose
    search failed and why)."""

    along: str
    members: list[RelativeEquilibrium]
    shape_names: list[str]
    group_names: list[str]
    values: np.ndarray
    shape: np.ndarray
    shape_momentum: np.ndarray
    momentum: np.ndarray
    group_velocity: np.ndarray
    multipliers: np.ndarray
    frequencies: np.ndarray
    stable: np.ndarray
    stability_changes: list[tuple[float, float]]
    folds: list["Fold"]
    ended: Optional[tuple[float, str]]

    def __init__(self, along: str, found: Mapping[str, Any]) -> None:
        self.along = along
        self.members = [RelativeEquilibrium(m) for m in found["members"]]
        first = self.members[0]
        self.shape_names, self.group_names = first.shape_names, first.group_names
        stack = lambda field: np.stack([getattr(m, field) for m in self.members])  # noqa: E731
        self.shape, self.shape_momentum = stack("shape"), stack("shape_momentum")
        self.momentum, self.group_velocity = stack("momentum"), stack("group_velocity")
        self.multipliers, self.frequencies = stack("multipliers"), stack("frequencies")
        self.stable = np.array([m.stable for m in self.members], dtype=bool)
        self.values = self.momentum[:, self.group_names.index(along)].copy()
        self.stability_changes = [(float(a), float(b)) for a, b in found["stability_changes"]]
        self.folds = [Fold(float(m), np.asarray(s, dtype=float), np.asarray(p, dtype=float), int(k))
                      for m, s, p, k in found["folds"]]
        ended = found["ended"]
        self.ended = None if ended is None else (float(ended[0]), str(ended[1]))

    def __len__(self) -> int:
        return len(self.members)

    def __repr__(self) -> str:
        end = "" if self.ended is None else f", ended at {self.along} momentum {self.ended[0]:.6g}"
        folds = "".join(f", a fold at {f.momentum:.6g}" for f in self.folds)
        return (f"ddirac.RelativeEquilibriumFamily({len(self)} members along the momentum of {self.along}, "
                f"{int(self.stable.sum())} stable{folds}{end})")


class Fold(NamedTuple):
    """A fold of a :class:`RelativeEquilibriumFamily`: where the momentum of ``along`` turns back
    (``momentum``), the shape there (``shape``, ``shape_momentum``, in the order of the family's
    ``shape_names``), and ``next_member``, the index of the family's first member past it."""

    momentum: float
    shape: np.ndarray
    shape_momentum: np.ndarray
    next_member: int


def relative_equilibria(system: System, momentum: Values, guess: Values, step: float,
                        shape_momentum: Optional[Values] = None, rule: str = "midpoint", variant: str = "plus",
                        reduced: bool = False, **method: Any) -> RelativeEquilibrium:
    """The relative equilibrium of the reduced discrete map of the method (``rule``, ``variant``,
    ``reduced`` and the other method keys of :func:`ddirac.simulate`) with the step ``step``, on the
    momentum level ``momentum`` (the group coordinates' momenta, in the order of ``system.group`` or by
    name), nearest (by Newton's method) to ``guess`` (the shape coordinates' values) and
    ``shape_momentum`` (their momenta; default 0). The same search as ``ddirac equilibria``:
    ``ddirac.relative_equilibria(pendulum, momentum=[1.6], guess={"theta": 1.0}, step=0.005)``.

    Returns a :class:`RelativeEquilibrium`; raises :class:`ddirac.Error` when the search fails (no
    convergence, a multiplier 1, a step that fails). An angle of the group that turns by more than
    π/2 in a step has its group velocity known only modulo 2π/h: that is warned."""
    args = _search_args(system, momentum, guess, step, shape_momentum, rule, variant, reduced, method)
    raw = _ddirac.relative_equilibrium(system._handle, args)
    found = RelativeEquilibrium(raw)
    _warn(found, raw["ambiguous"])
    return found


def relative_equilibrium_family(system: System, along: str, values: Sequence[float], guess: Values, step: float,
                                momentum: Optional[Values] = None, shape_momentum: Optional[Values] = None,
                                rule: str = "midpoint", variant: str = "plus", reduced: bool = False,
                                **method: Any) -> RelativeEquilibriumFamily:
    """The family of relative equilibria through the one :func:`relative_equilibria` finds from
    ``guess`` at the first of ``values``, continued along the momentum of the group coordinate
    ``along`` over ``values`` (natural continuation: each member's search starts from the members
    before; where a search fails, pseudo-arclength continuation reaches the value or passes a fold, past
    which the family continues on its other branch over the values already visited), the other group
    momenta held at ``momentum`` (default 0; its entry for ``along`` is replaced). The same search as ``ddirac equilibria --family``:
    ``ddirac.relative_equilibrium_family(pendulum, along="phi", values=np.linspace(0.5, 3, 11),
    guess={"theta": 0.5}, step=0.005)``.

    Returns a :class:`RelativeEquilibriumFamily`. Raises :class:`ddirac.Error` when ``along`` is not a
    group coordinate, ``values`` is empty or not finite, or the first search fails; a later failure
    ends the family (its ``ended``, also warned)."""
    _searchable(system)
    if not isinstance(along, str):
        raise _ddirac.Error(f"`along` must be the name of a group coordinate, not {type(along).__name__}")
    try:
        points = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise _ddirac.Error(f"`values` must be a sequence of numbers: {error}") from None
    if points.ndim != 1:
        raise _ddirac.Error(f"`values` must be one-dimensional (the momenta of `{along}`), not of shape {points.shape}")
    if points.size == 0:
        raise _ddirac.Error("`values` is empty: the family needs at least one value of the momentum")
    bad = [v for v in points if not math.isfinite(v)]
    if bad:
        raise _ddirac.Error(f"`values` holds {bad[0]}, which is not a finite number")
    group = list(system.group)
    level = dict(zip(group, _by_name(momentum, group, "momentum")))
    if along in level:
        level[along] = float(points[0])
    args = _search_args(system, level, guess, step, shape_momentum, rule, variant, reduced, method)
    raw = _ddirac.relative_equilibrium_family(system._handle, args, along, [float(v) for v in points])
    found = RelativeEquilibriumFamily(along, raw)
    for member, member_raw in zip(found.members, raw["members"]):
        _warn(member, member_raw["ambiguous"])
    if found.ended is not None:
        warnings.warn(f"the family ends at the momentum {found.ended[0]:.6g} of `{along}` ({len(found)} of "
                      f"{points.size} values found): {found.ended[1]}", UserWarning, stacklevel=2)
    return found


def _search_args(system: System, momentum: Optional[Values], guess: Values, step: float,
                 shape_momentum: Optional[Values], rule: str, variant: str, reduced: bool,
                 method: Mapping[str, Any]) -> dict[str, Any]:
    """The run arguments of a search: q0 from the shape guess, p0 from the momentum level and the
    shape momenta."""
    from .run import _prepare

    _searchable(system)
    names = system.coordinates
    group = list(system.group)
    shape = [n for n in names if n not in group]
    mu = dict(zip(group, _by_name(momentum, group, "momentum")))
    s = dict(zip(shape, _by_name(guess, shape, "guess")))
    ps = dict(zip(shape, _by_name(shape_momentum, shape, "shape_momentum")))
    q0 = [s.get(n, 0.0) for n in names]
    p0 = [ps[n] if n in ps else mu[n] for n in names]
    return _prepare(system, q0, p0, None, step, 1, None, rule, variant, reduced, method)


def _searchable(system: Any) -> None:
    """An error unless the searches take ``system``: a :class:`ddirac.System` other than a rigid body."""
    from .rigid import RigidBody

    if isinstance(system, RigidBody):
        raise _ddirac.Error("relative equilibria of rigid bodies are not searched yet")
    if not isinstance(system, System):
        raise _ddirac.Error(f"`system` must be a ddirac.System, not {type(system).__name__}")


def _warn(found: RelativeEquilibrium, ambiguous: Sequence[str]) -> None:
    """The warnings of a relative equilibrium found: a group velocity known only modulo 2π/h, a map
    that does not preserve volume."""
    for name in ambiguous:
        warnings.warn(f"`{name}` turns by more than π/2 in a step of h = {found.step}: its group velocity is known "
                      f"only modulo 2π/h = {2 * math.pi / found.step:.6g}; take a smaller step to know it",
                      UserWarning, stacklevel=3)
    if abs(found.determinant - 1.0) > 1e-6:
        warnings.warn(f"det DΦ_h = {found.determinant:.6g} at the relative equilibrium, not 1: the map does not "
                      f"preserve volume on this level, and the multipliers need not pair as a symplectic map's",
                      UserWarning, stacklevel=3)
