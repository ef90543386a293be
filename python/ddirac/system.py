"""Systems: built-in ones, and systems whose Lagrangian is text (as the ``[system]`` table of a spec)."""

from __future__ import annotations

import sys
from typing import Any, Iterable, Mapping, Optional

from . import _ddirac

#: A coordinate's name: a string, or a SymPy symbol ``q`` or dynamicsymbol ``q(t)`` of that name.
CoordinateName = Any


class System:
    """A mechanical system: coordinates (shape and group), a Lagrangian L(q, q̇), parameters.

    ``System(lagrangian=..., shape=[...], group=[...], angles=[...], definitions={...},
    parameters={...})`` compiles a Lagrangian written as text: an expression in the coordinates, their
    velocities ``<name>_dot``, the parameters and the definitions (named expressions), with ``sin``,
    ``cos``, ``exp``, ``sqrt``, ``min``, ``max``, ``atan2`` and the rest of the expression language of
    spec files. The coordinates are ``shape`` then ``group`` (or the permutation ``order``); the group
    coordinates are those the symmetry translates, and ``angles`` lists those on the circle.
    ``exact`` gives exact solutions by coordinate, as expressions in ``t`` and the parameters.

    The Lagrangian, the definitions and the exact solutions may also be SymPy expressions: velocities
    as symbols ``<name>_dot``, or ``sympy.physics.mechanics.dynamicsymbols`` and their first derivatives
    (SymPy is imported only then). Wherever a coordinate is named (``shape``, ``group``, ``angles``,
    ``order``, the keys of ``exact``, and of ``q0``, ``p0``, ``v0`` given as dicts), a SymPy symbol
    ``q`` or dynamicsymbol ``q(t)`` names the coordinate ``q``, and the keys of ``v0`` may be the
    velocities ``q(t).diff(t)``::

        from sympy import cos
        from sympy.physics.mechanics import dynamicsymbols

        th, t = dynamicsymbols("th"), dynamicsymbols._t
        pendulum = ddirac.System(lagrangian=th.diff(t)**2 / 2 + cos(th), shape=[th], angles=[th])
        ddirac.simulate(pendulum, q0={th: 1.0}, v0={th.diff(t): 0.0}, step=0.01, steps=100)

    ``System.builtin(name, **parameters)`` is a built-in system (see :func:`builtin_systems`).
    """

    def __init__(self, lagrangian: Any, shape: Iterable[CoordinateName] = (), group: Iterable[CoordinateName] = (),
                 angles: Iterable[CoordinateName] = (), definitions: Optional[Mapping[Any, Any]] = None,
                 parameters: Optional[Mapping[Any, float]] = None, exact: Optional[Mapping[CoordinateName, Any]] = None,
                 order: Optional[Iterable[CoordinateName]] = None, name: Optional[str] = None) -> None:
        shape, group = _names(shape, "shape"), _names(group, "group")
        coordinates = shape + group
        if not isinstance(lagrangian, str):
            lagrangian = _from_sympy(lagrangian, coordinates, "lagrangian")
        definitions = {str(k): v if isinstance(v, str) else _from_sympy(v, coordinates, f"definition `{k}`")
                       for k, v in (definitions or {}).items()}
        exact = {coordinate_name(k, "a key of `exact`"): v if isinstance(v, str)
                 else _from_sympy(v, [], f"exact solution of `{k}`") for k, v in (exact or {}).items()}
        self._handle = _ddirac.text_system(
            lagrangian,
            shape,
            group,
            _names(angles, "angles"),
            [(k, str(v)) for k, v in definitions.items()],
            [(str(k), _number(v, f"parameter `{k}`")) for k, v in (parameters or {}).items()],
            [(k, str(v)) for k, v in exact.items()],
            None if order is None else _names(order, "order"),
            name,
        )

    @classmethod
    def _from_handle(cls, handle: _ddirac.SystemHandle) -> System:
        system = cls.__new__(cls)
        system._handle = handle
        return system

    @classmethod
    def builtin(cls, name: str, **parameters: float) -> System:
        """The built-in system ``name`` with some parameters overridden, e.g.
        ``System.builtin("pendulum_chain", links=8)``; ``System.builtin("rigid_body", ...)`` is a
        :class:`ddirac.RigidBody`."""
        if str(name) == "rigid_body":
            from .rigid import RigidBody

            return RigidBody._builtin(**parameters)
        system = cls.__new__(cls)
        overrides = [(str(k), _number(v, f"parameter `{k}`")) for k, v in parameters.items()]
        system._handle = _ddirac.builtin_system(str(name), overrides)
        return system

    @property
    def name(self) -> str:
        """The name ``summary.json`` gives the system."""
        return self._handle.name

    @property
    def parameters(self) -> dict[str, float]:
        """The parameters, by name."""
        return dict(self._handle.parameters)

    @property
    def coordinates(self) -> list[str]:
        """The coordinate names, in the order of ``q`` and ``p``."""
        return [name for name, _, _ in self._handle.coordinates]

    @property
    def shape(self) -> list[str]:
        """The shape coordinates (the reduced space Σ)."""
        return [name for name, role, _ in self._handle.coordinates if role == "shape"]

    @property
    def group(self) -> list[str]:
        """The group coordinates (translated by the symmetry)."""
        return [name for name, role, _ in self._handle.coordinates if role == "group"]

    @property
    def angles(self) -> list[str]:
        """The coordinates on the circle."""
        return [name for name, _, kind in self._handle.coordinates if kind == "angle"]

    def __repr__(self) -> str:
        return f"ddirac.System({self.name!r}, coordinates={self.coordinates})"


def builtin_systems() -> dict[str, str]:
    """The built-in systems: name → one-line description."""
    names = dict(_ddirac.builtin_names())
    names["rigid_body"] = ("a rigid body on SO(3) about a fixed point in gravity (a free body when m·g·|c| = 0): "
                           "ddirac.simulate(body, R0=..., Pi0=... or Omega0=...)")
    return names


def is_sympy(value: Any) -> bool:
    """Whether ``value`` is a SymPy object (without importing SymPy: none is unless it is imported)."""
    sympy = sys.modules.get("sympy")
    return sympy is not None and isinstance(value, sympy.Basic)


def _from_sympy(expression: Any, coordinates: list[str], what: str) -> str:
    """The text of a SymPy expression; SymPy is imported only here."""
    if not is_sympy(expression):
        raise _ddirac.Error(f"the {what} must be a string or a SymPy expression, not {type(expression).__name__}")
    from .sympy_text import to_text

    try:
        return to_text(expression, coordinates)
    except ValueError as e:
        raise _ddirac.ExpressionError(f"the {what}: {e}") from None


def coordinate_name(value: CoordinateName, what: str, velocity: bool = False) -> str:
    """The name of the coordinate ``value`` names (a string; a SymPy symbol ``q`` or dynamicsymbol
    ``q(t)``); with ``velocity``, a key that may also be the velocity ``q(t).diff(t)``, which names ``q``
    too. ``what`` says where the name was given, for the error."""
    return _coordinate_key(value, what, velocity)[0]


def _coordinate_key(value: CoordinateName, what: str, velocity: bool = False) -> tuple[str, bool]:
    """:func:`coordinate_name` and whether ``value`` is a velocity."""
    if isinstance(value, str):
        return value, False
    if is_sympy(value):
        from .sympy_text import coordinate_name as sympy_name

        try:
            return sympy_name(value, velocity)
        except ValueError as e:
            raise _ddirac.Error(f"{what}: {e}") from None
    return str(value), False


def _names(values: Iterable[CoordinateName], what: str) -> list[str]:
    if isinstance(values, str) or is_sympy(values):
        raise _ddirac.Error(f"`{what}` must be a list of names, not the single {type(values).__name__} {values!r}")
    return [coordinate_name(v, f"`{what}`") for v in values]


def _number(value: Any, what: str) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise _ddirac.Error(f"{what} must be a number, not {value!r}") from None
