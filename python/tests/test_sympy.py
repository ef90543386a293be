"""Lagrangians given as SymPy expressions: symbols `<name>_dot`, or dynamicsymbols and their derivatives."""

import numpy as np
import pytest

import ddirac

sp = pytest.importorskip("sympy")

TEXT = "0.5*m*l^2*(theta_dot^2 + sin(theta)^2*phi_dot^2) + m*g*l*cos(theta)"
PARAMETERS = {"m": 1.0, "l": 1.0, "g": 9.8}


def run(system):
    return ddirac.simulate(system, q0=[1.0, 0.0], v0=[0.0, 2.0], step=0.005, steps=2000, reduced=True)


def pendulum(lagrangian):
    return ddirac.System(lagrangian=lagrangian, shape=["theta"], group=["phi"], angles=["theta", "phi"],
                         parameters=PARAMETERS)


def test_a_sympy_lagrangian_with_velocity_symbols_gives_the_trajectory_of_the_text_one():
    theta, phi, theta_dot, phi_dot, m, g, l = sp.symbols("theta phi theta_dot phi_dot m g l")
    lagrangian = sp.Rational(1, 2) * m * l**2 * (theta_dot**2 + sp.sin(theta)**2 * phi_dot**2) + m * g * l * sp.cos(theta)
    a, b = run(pendulum(lagrangian)), run(pendulum(TEXT))
    assert np.max(np.abs(a.q - b.q)) < 1e-12 and np.max(np.abs(a.p - b.p)) < 1e-12


def test_a_lagrangian_in_dynamicsymbols_gives_the_same_trajectory():
    from sympy.physics.mechanics import dynamicsymbols

    theta, phi = dynamicsymbols("theta phi")
    t = dynamicsymbols._t
    m, g, l = sp.symbols("m g l")
    lagrangian = (m * l**2 * (theta.diff(t)**2 + sp.sin(theta)**2 * phi.diff(t)**2) / 2
                  + m * g * l * sp.cos(theta))
    a, b = run(pendulum(lagrangian)), run(pendulum(TEXT))
    assert np.max(np.abs(a.q - b.q)) < 1e-12


def test_powers_roots_signs_and_piecewise_functions_print_with_their_meaning():
    x, x_dot = sp.symbols("x x_dot")
    potential = -x**2 / 4 + sp.sqrt(1 + x**2) + sp.Abs(x)**3 + sp.Max(x, 0)**2 - sp.Rational(3, 2) * x**sp.Rational(3, 2) \
        + sp.log(2 + x**2) + sp.exp(-x**2)
    system = ddirac.System(lagrangian=x_dot**2 / 2 - potential, shape=["x"])
    text = ddirac.System(lagrangian=(
        "0.5*x_dot^2 - (-(x^2)/4 + sqrt(1 + x^2) + abs(x)^3 + max(x, 0)^2 - 1.5*x^1.5 + ln(2 + x^2) + exp(-(x^2)))"),
        shape=["x"])
    a = ddirac.simulate(system, q0=[0.7], p0=[0.0], step=0.01, steps=300)
    b = ddirac.simulate(text, q0=[0.7], p0=[0.0], step=0.01, steps=300)
    assert np.max(np.abs(a.q - b.q)) < 1e-12


def test_a_second_derivative_is_refused_as_an_expression_error():
    from sympy.physics.mechanics import dynamicsymbols

    x = dynamicsymbols("x")
    t = dynamicsymbols._t
    with pytest.raises(ddirac.ExpressionError, match="order above one"):
        ddirac.System(lagrangian=x.diff(t, 2) * x, shape=["x"])
