"""SymPy expressions as text of the expression language (imported only when a Lagrangian is one).

Velocities are symbols ``<name>_dot``, or the derivatives of ``sympy.physics.mechanics.dynamicsymbols``:
``q(t)`` becomes ``q`` and ``Derivative(q(t), t)`` becomes ``q_dot``. Powers print as ``^``, ``log`` as
``ln``, ``Abs`` as ``abs``, n-ary ``Min``/``Max`` as nested ``min``/``max``, numbers exactly (rationals
as quotients, floats with every digit of their double).
"""

from __future__ import annotations

from typing import Any, Sequence

import sympy
from sympy.core.function import AppliedUndef
from sympy.printing.str import StrPrinter


def is_sympy(value: Any) -> bool:
    """Whether ``value`` is a SymPy object."""
    return isinstance(value, sympy.Basic)


def _coordinate_function(value: Any) -> bool:
    """Whether ``value`` is a dynamicsymbol: an undefined function applied to one symbol, ``q(t)``."""
    return isinstance(value, AppliedUndef) and len(value.args) == 1 and value.args[0].is_Symbol


def coordinate_name(value: Any, velocity: bool = False) -> tuple[str, bool]:
    """The coordinate a SymPy object names, and whether it names its velocity: a symbol ``q`` or a
    dynamicsymbol ``q(t)`` names the coordinate ``q``; with ``velocity``, the first derivative
    ``q(t).diff(t)`` names the velocity of ``q``. Raises ``ValueError`` saying why for anything else."""
    if isinstance(value, sympy.Symbol):
        return value.name, False
    if _coordinate_function(value):
        return type(value).__name__, False
    if isinstance(value, sympy.Derivative) and _coordinate_function(value.expr):
        counts = value.variable_count
        if len(counts) == 1 and counts[0][0] == value.expr.args[0] and counts[0][1] == 1:
            if velocity:
                return type(value.expr).__name__, True
            raise ValueError(f"`{value}` is a velocity, not a coordinate; name the coordinate "
                             f"`{value.expr}` itself")
        raise ValueError(f"`{value}` is not a first derivative of a coordinate in time")
    raise ValueError(f"`{value}` ({type(value).__name__}) names no coordinate: give a string, a SymPy symbol or "
                     f"a `sympy.physics.mechanics.dynamicsymbols` function such as `q(t)`")


def to_text(expression: Any, coordinates: Sequence[str]) -> str:
    """The text of ``expression`` in the expression language, with the coordinates' dynamicsymbols
    and their time derivatives replaced by the coordinates and their velocities."""
    expression = sympy.sympify(expression)
    replacements = {}
    for function in expression.atoms(AppliedUndef):
        name = type(function).__name__
        if name in coordinates and _coordinate_function(function):
            time = function.args[0]
            replacements[sympy.Derivative(function, time)] = sympy.Symbol(f"{name}_dot")
            replacements[function] = sympy.Symbol(name)
    derivatives = {k: v for k, v in replacements.items() if isinstance(k, sympy.Derivative)}
    expression = expression.xreplace(derivatives).xreplace(replacements)
    unknown = sorted(expression.atoms(AppliedUndef), key=str)
    listed = ", ".join(coordinates) or "none"
    if unknown:
        raise ValueError(f"`{unknown[0]}` is a function of time that is not a coordinate (the coordinates are: "
                         f"{listed}); declare it in `shape` or `group`, or write a constant as a parameter")
    leftover = sorted(expression.atoms(sympy.Derivative), key=str)
    if leftover:
        raise ValueError(f"`{leftover[0]}` is a derivative of order above one; the Lagrangian takes the coordinates "
                         f"({listed}) and their first derivatives only")
    return _Printer().doprint(expression)


class _Printer(StrPrinter):  # type: ignore[misc]
    def _print_Pow(self, expr: Any) -> str:
        base, exponent = expr.as_base_exp()
        if exponent == sympy.Rational(1, 2):
            return f"sqrt({self._print(base)})"
        if exponent == -1:
            return f"1/{self.parenthesize(base, 100)}"
        return f"{self.parenthesize(base, 100)}^{self.parenthesize(exponent, 100)}"

    def _print_Rational(self, expr: Any) -> str:
        return f"({expr.p}/{expr.q})"

    def _print_Float(self, expr: Any) -> str:
        return repr(float(expr))

    def _print_Integer(self, expr: Any) -> str:
        return str(int(expr))

    def _print_Exp1(self, expr: Any) -> str:
        return "exp(1)"

    def _print_Pi(self, expr: Any) -> str:
        return "pi"

    def _print_log(self, expr: Any) -> str:
        return f"ln({self._print(expr.args[0])})"

    def _print_Abs(self, expr: Any) -> str:
        return f"abs({self._print(expr.args[0])})"

    def _nested(self, name: str, args: Sequence[Any]) -> str:
        text = self._print(args[-1])
        for arg in reversed(args[:-1]):
            text = f"{name}({self._print(arg)}, {text})"
        return text

    def _print_Min(self, expr: Any) -> str:
        return self._nested("min", expr.args)

    def _print_Max(self, expr: Any) -> str:
        return self._nested("max", expr.args)
