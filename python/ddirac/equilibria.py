"""Relative equilibria of the reduced discrete map on a momentum level (:func:`relative_equilibria`),
as ``ddirac equilibria`` finds them."""

from __future__ import annotations

import math
import warnings
from typing import Any, Mapping, Optional, Sequence, Union

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
    from .run import _prepare
    from .rigid import RigidBody

    if isinstance(system, RigidBody):
        raise _ddirac.Error("relative_equilibria does not take rigid bodies yet")
    if not isinstance(system, System):
        raise _ddirac.Error(f"`system` must be a ddirac.System, not {type(system).__name__}")
    names = system.coordinates
    group = list(system.group)
    shape = [n for n in names if n not in group]
    mu = dict(zip(group, _by_name(momentum, group, "momentum")))
    s = dict(zip(shape, _by_name(guess, shape, "guess")))
    ps = dict(zip(shape, _by_name(shape_momentum, shape, "shape_momentum")))
    q0 = [s.get(n, 0.0) for n in names]
    p0 = [ps[n] if n in ps else mu[n] for n in names]
    args = _prepare(system, q0, p0, None, step, 1, None, rule, variant, reduced, method)
    raw = _ddirac.relative_equilibrium(system._handle, args)
    found = RelativeEquilibrium(raw)
    for name in raw["ambiguous"]:
        warnings.warn(f"`{name}` turns by more than π/2 in a step of h = {found.step}: its group velocity is known "
                      f"only modulo 2π/h = {2 * math.pi / found.step:.6g}; take a smaller step to know it",
                      UserWarning, stacklevel=2)
    if abs(found.determinant - 1.0) > 1e-6:
        warnings.warn(f"det DΦ_h = {found.determinant:.6g} at the relative equilibrium, not 1: the map does not "
                      f"preserve volume on this level, and the multipliers need not pair as a symplectic map's",
                      UserWarning, stacklevel=2)
    return found
