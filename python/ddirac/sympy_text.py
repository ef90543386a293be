"""SymPy expressions as text of the expression language (imported only when a Lagrangian is one).

Velocities are symbols ``<name>_dot``, or the derivatives of ``sympy.physics.mechanics.dynamicsymbols``:
``q(t)`` becomes ``q`` and ``Derivative(q(t), t)`` becomes ``q_dot``. Powers print as ``^``, ``log`` as
``ln``, ``Abs`` as ``abs``, n-ary ``Min``/``Max`` as nested ``min``/``max``, numbers exactly (rationals
as quotients, floats with every digit of their double).
"""

import sympy
from sympy.printing.str import StrPrinter


def is_sympy(value):
    """Whether ``value`` is a SymPy expression (without importing SymPy for other values)."""
    return type(value).__module__.startswith("sympy")


def to_text(expression, coordinates):
    """The text of ``expression`` in the expression language, with the coordinates' dynamicsymbols
    and their time derivatives replaced by the coordinates and their velocities."""
    expression = sympy.sympify(expression)
    replacements = {}
    for function in expression.atoms(sympy.Function):
        name = type(function).__name__
        if name in coordinates and len(function.args) == 1 and function.args[0].is_Symbol:
            time = function.args[0]
            replacements[sympy.Derivative(function, time)] = sympy.Symbol(f"{name}_dot")
            replacements[function] = sympy.Symbol(name)
    derivatives = {k: v for k, v in replacements.items() if isinstance(k, sympy.Derivative)}
    expression = expression.xreplace(derivatives).xreplace(replacements)
    leftover = [d for d in expression.atoms(sympy.Derivative)]
    if leftover:
        raise ValueError(f"the Lagrangian has derivatives of order above one or of unknown functions: {leftover[0]}")
    return _Printer().doprint(expression)


class _Printer(StrPrinter):
    def _print_Pow(self, expr):
        base, exponent = expr.as_base_exp()
        if exponent == sympy.Rational(1, 2):
            return f"sqrt({self._print(base)})"
        if exponent == -1:
            return f"1/{self.parenthesize(base, 100)}"
        return f"{self.parenthesize(base, 100)}^{self.parenthesize(exponent, 100)}"

    def _print_Rational(self, expr):
        return f"({expr.p}/{expr.q})"

    def _print_Float(self, expr):
        return repr(float(expr))

    def _print_Integer(self, expr):
        return str(int(expr))

    def _print_Exp1(self, expr):
        return "exp(1)"

    def _print_Pi(self, expr):
        return "pi"

    def _print_log(self, expr):
        return f"ln({self._print(expr.args[0])})"

    def _print_Abs(self, expr):
        return f"abs({self._print(expr.args[0])})"

    def _nested(self, name, args):
        text = self._print(args[-1])
        for arg in reversed(args[:-1]):
            text = f"{name}({self._print(arg)}, {text})"
        return text

    def _print_Min(self, expr):
        return self._nested("min", expr.args)

    def _print_Max(self, expr):
        return self._nested("max", expr.args)
