"""SymPy dynamicsymbols (and symbols) name coordinates wherever a coordinate name is taken — shape,
group, angles, order, exact, and the keys of q0, p0 and v0 (v0 also by the derivative q(t).diff(t)) —
and a system so named runs bit for bit as the one named by strings."""

import numpy as np
import pytest

import ddirac

sp = pytest.importorskip("sympy")
from sympy.physics.mechanics import dynamicsymbols  # noqa: E402

TEXT = "0.5*m*l^2*(theta_dot^2 + sin(theta)^2*phi_dot^2) + m*g*l*cos(theta)"
PARAMETERS = {"m": 1.0, "l": 1.0, "g": 9.8}
RUN = dict(step=0.01, steps=200, rule="midpoint")


def lagrangian(theta, phi):
    t = dynamicsymbols._t
    m, g, l = sp.symbols("m g l")
    return m * l**2 * (theta.diff(t)**2 + sp.sin(theta)**2 * phi.diff(t)**2) / 2 + m * g * l * sp.cos(theta)


def same(a, b):
    for name in ("t", "q", "p", "energy", "discrete_energy", "momentum_map"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_dynamicsymbols_as_shape_group_and_angles_run_as_strings_do():
    theta, phi = dynamicsymbols("theta phi")
    t = dynamicsymbols._t
    symbolic = ddirac.System(lagrangian=lagrangian(theta, phi), shape=[theta], group=[phi], angles=[theta, phi],
                             parameters=PARAMETERS)
    text = ddirac.System(lagrangian=TEXT, shape=["theta"], group=["phi"], angles=["theta", "phi"],
                         parameters=PARAMETERS)
    assert symbolic.coordinates == text.coordinates == ["theta", "phi"]
    assert symbolic.angles == text.angles and symbolic.group == ["phi"]
    for reduced in (False, True):
        a = ddirac.simulate(symbolic, q0={theta: 1.0, phi: 0.0}, v0={theta.diff(t): 0.0, phi.diff(t): 2.0},
                            reduced=reduced, **RUN)
        b = ddirac.simulate(text, q0={"theta": 1.0, "phi": 0.0}, v0={"theta": 0.0, "phi": 2.0}, reduced=reduced,
                            **RUN)
        same(a, b)
    # p0 by dynamicsymbol, and v0 by the coordinates themselves.
    same(ddirac.simulate(symbolic, q0={theta: 1.0, phi: 0.0}, p0={theta: 0.0, phi: 0.5}, **RUN),
         ddirac.simulate(text, q0=[1.0, 0.0], p0=[0.0, 0.5], **RUN))
    same(ddirac.simulate(symbolic, q0={theta: 1.0, phi: 0.0}, v0={theta: 0.0, phi: 2.0}, **RUN),
         ddirac.simulate(text, q0=[1.0, 0.0], v0=[0.0, 2.0], **RUN))
    # check takes them too.
    assert ddirac.check(symbolic, q0={theta: 1.0, phi: 0.0}, v0={theta.diff(t): 0.0, phi: 2.0}, **RUN)["verdict"] \
        == ddirac.check(text, q0=[1.0, 0.0], v0=[0.0, 2.0], **RUN)["verdict"]


def test_order_and_exact_take_dynamicsymbols_and_plain_symbols():
    x, y = dynamicsymbols("x y")
    t = dynamicsymbols._t
    xs = sp.Symbol("x")
    free = x.diff(t)**2 / 2 + y.diff(t)**2 / 2
    symbolic = ddirac.System(lagrangian=free, shape=[xs], group=[y], order=[y, x],
                             exact={x: sp.Integer(1) + t, y: "2*t"})
    text = ddirac.System(lagrangian="0.5*x_dot^2 + 0.5*y_dot^2", shape=["x"], group=["y"], order=["y", "x"],
                         exact={"x": "1 + t", "y": "2*t"})
    assert symbolic.coordinates == text.coordinates == ["y", "x"]
    a = ddirac.simulate(symbolic, q0={x: 1.0, y: 0.0}, v0={x.diff(t): 1.0, y.diff(t): 2.0}, **RUN)
    b = ddirac.simulate(text, q0={"x": 1.0, "y": 0.0}, v0={"x": 1.0, "y": 2.0}, **RUN)
    same(a, b)
    assert a.summary["reference_error"] == b.summary["reference_error"] is not None


def test_what_names_no_coordinate_is_refused_saying_why():
    x = dynamicsymbols("x")
    t = dynamicsymbols._t
    system = ddirac.System(lagrangian=x.diff(t)**2 / 2, shape=[x])
    with pytest.raises(ddirac.Error, match="is a velocity, not a coordinate"):
        ddirac.simulate(system, q0={x.diff(t): 0.0}, v0=[1.0], **RUN)
    with pytest.raises(ddirac.Error, match="not a first derivative"):
        ddirac.simulate(system, q0=[0.0], v0={x.diff(t, 2): 1.0}, **RUN)
    with pytest.raises(ddirac.Error, match="gives coordinate `x` twice"):
        ddirac.simulate(system, q0=[0.0], v0={x: 1.0, x.diff(t): 1.0}, **RUN)
    with pytest.raises(ddirac.Error, match="names no coordinate"):
        ddirac.System(lagrangian=x.diff(t)**2 / 2, shape=[x + 1])
    # A function of time in the Lagrangian that is not declared a coordinate is named as such.
    y = dynamicsymbols("y")
    with pytest.raises(ddirac.ExpressionError, match=r"`y\(t\)` is a function of time that is not a coordinate"):
        ddirac.System(lagrangian=x.diff(t)**2 / 2 + y, shape=[x])
