"""Systems: built-in ones, and systems whose Lagrangian is text (as the ``[system]`` table of a spec)."""

from . import _ddirac


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
    (SymPy is imported only then).

    ``System.builtin(name, **parameters)`` is a built-in system (see :func:`builtin_systems`).
    """

    def __init__(self, lagrangian, shape=(), group=(), angles=(), definitions=None, parameters=None,
                 exact=None, order=None, name=None):
        if not isinstance(lagrangian, str):
            lagrangian = _from_sympy(lagrangian, list(shape) + list(group), "lagrangian")
        definitions = {k: v if isinstance(v, str) else _from_sympy(v, list(shape) + list(group), f"definition `{k}`")
                       for k, v in (definitions or {}).items()}
        exact = {k: v if isinstance(v, str) else _from_sympy(v, [], f"exact solution of `{k}`")
                 for k, v in (exact or {}).items()}
        self._handle = _ddirac.text_system(
            lagrangian,
            _names(shape, "shape"),
            _names(group, "group"),
            _names(angles, "angles"),
            [(str(k), str(v)) for k, v in definitions.items()],
            [(str(k), _number(v, f"parameter `{k}`")) for k, v in (parameters or {}).items()],
            [(str(k), str(v)) for k, v in exact.items()],
            None if order is None else _names(order, "order"),
            name,
        )

    @classmethod
    def _from_handle(cls, handle):
        system = cls.__new__(cls)
        system._handle = handle
        return system

    @classmethod
    def builtin(cls, name, **parameters):
        """The built-in system ``name`` with some parameters overridden, e.g.
        ``System.builtin("pendulum_chain", links=8)``."""
        system = cls.__new__(cls)
        overrides = [(str(k), _number(v, f"parameter `{k}`")) for k, v in parameters.items()]
        system._handle = _ddirac.builtin_system(str(name), overrides)
        return system

    @property
    def name(self):
        """The name ``summary.json`` gives the system."""
        return self._handle.name

    @property
    def parameters(self):
        """The parameters, by name."""
        return dict(self._handle.parameters)

    @property
    def coordinates(self):
        """The coordinate names, in the order of ``q`` and ``p``."""
        return [name for name, _, _ in self._handle.coordinates]

    @property
    def shape(self):
        """The shape coordinates (the reduced space Σ)."""
        return [name for name, role, _ in self._handle.coordinates if role == "shape"]

    @property
    def group(self):
        """The group coordinates (translated by the symmetry)."""
        return [name for name, role, _ in self._handle.coordinates if role == "group"]

    @property
    def angles(self):
        """The coordinates on the circle."""
        return [name for name, _, kind in self._handle.coordinates if kind == "angle"]

    def __repr__(self):
        return f"ddirac.System({self.name!r}, coordinates={self.coordinates})"


def builtin_systems():
    """The built-in systems: name → one-line description."""
    return dict(_ddirac.builtin_names())


def _from_sympy(expression, coordinates, what):
    """The text of a SymPy expression; SymPy is imported only here."""
    if not type(expression).__module__.startswith("sympy"):
        raise _ddirac.Error(f"the {what} must be a string or a SymPy expression, not {type(expression).__name__}")
    from .sympy_text import to_text

    try:
        return to_text(expression, [str(c) for c in coordinates])
    except ValueError as e:
        raise _ddirac.ExpressionError(f"the {what}: {e}") from None


def _names(values, what):
    if isinstance(values, str):
        raise _ddirac.Error(f"`{what}` must be a list of names, not the string {values!r}")
    return [str(v) for v in values]


def _number(value, what):
    try:
        return float(value)
    except (TypeError, ValueError):
        raise _ddirac.Error(f"{what} must be a number, not {value!r}") from None
