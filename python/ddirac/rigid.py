"""Rigid bodies on SO(3): the built-in :class:`RigidBody` and the :class:`RigidRun` of
:func:`ddirac.simulate` on it.

The attitude R (body to space) is advanced on the rotation group itself, with no angles, so no
attitude is singular; the body angular momentum Π and the spatial angular momentum R Π come with it::

    body = ddirac.System.builtin("rigid_body", I1=1.0, I2=2.0, I3=3.0, m=0.0)   # a free body
    run = ddirac.simulate(body, R0=np.eye(3), Omega0=[0.01, 2.0, 0.01], step=0.01, duration=40.0,
                          reduced=True)
    run.R          # (rows, 3, 3): R_k, body to space
    run.Pi         # (rows, 3): the body angular momentum Π_k
    run.momentum_map, run.energy, run.summary
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterable, Mapping, Optional, Sequence

import numpy as np

from . import _ddirac
from .run import Run
from .system import System

if TYPE_CHECKING:  # optional: imported by the methods that need them
    import pandas


class RigidBody(System):
    """A rigid system on SO(3) × S: an attitude R (body to space) and shape coordinates s, with a
    Lagrangian ℓ(R, Ω, s, ṡ) in the body angular velocity Ω.

    ``System.builtin("rigid_body", **parameters)`` is the built-in body about a fixed point in gravity
    −g e3, ℓ = ½ (I1 Ω1² + I2 Ω2² + I3 Ω3²) − m g ⟨e3, R c⟩, with parameters ``I1``, ``I2``, ``I3``
    (principal moments), ``m``, ``g``, ``c1``, ``c2``, ``c3`` (the centre of mass in the body frame); it has
    no shape coordinates. ``RigidBody(lagrangian, symmetry, shape=[...], angles=[...], definitions={...},
    parameters={...})`` is one written as text, as a spec's ``[system]`` table with ``attitude = "SO(3)"``:
    an expression in ``Omega1`` … ``Omega3``, the attitude's entries ``R11`` … ``R33``, the shape
    coordinates and their velocities ``<name>_dot``, the parameters and the definitions. ``symmetry``
    declares the rotations of space leaving it invariant: ``"SO(3)"`` (every rotation: reducible),
    ``"vertical"`` (about e3) or ``"none"``; a run tests it before its first step::

        satellite = ddirac.RigidBody("0.5*(J1*Omega1^2 + J2*Omega2^2 + J3*Omega3^2) + 0.5*K*(Omega3 + a_dot)^2",
                                     symmetry="SO(3)", shape=["a"], angles=["a"],
                                     parameters={"J1": 1, "J2": 2, "J3": 3, "K": 0.1})
        run = ddirac.simulate(satellite, R0=np.eye(3), Omega0=[0.01, 2, 0.01], q0=[0.0], v0=[30.0],
                              step=0.01, steps=1000, reduced=True)

    :func:`ddirac.simulate` takes the attitude as ``R0`` with ``Pi0`` or ``Omega0``, and the shape (if any)
    as ``q0`` with ``p0`` (beside ``Pi0``) or ``v0`` (beside ``Omega0``).
    """

    def __init__(self, lagrangian: Any, symmetry: str, shape: Iterable[str] = (), angles: Iterable[str] = (),
                 definitions: Optional[Mapping[str, Any]] = None, parameters: Optional[Mapping[str, float]] = None,
                 name: Optional[str] = None) -> None:
        from .system import _from_sympy, _names, _number

        shape, angles = _names(shape, "shape"), _names(angles, "angles")
        if not isinstance(lagrangian, str):
            lagrangian = _from_sympy(lagrangian, shape, "lagrangian")
        self._rigid = _ddirac.rigid_text_system(
            lagrangian, shape, angles,
            [(str(k), v if isinstance(v, str) else _from_sympy(v, shape, f"definition `{k}`"))
             for k, v in (definitions or {}).items()],
            [(str(k), _number(v, f"parameter `{k}`")) for k, v in (parameters or {}).items()],
            str(symmetry), name)

    @classmethod
    def _builtin(cls, **parameters: float) -> RigidBody:
        from .system import _number

        body = cls.__new__(cls)
        body._rigid = _ddirac.rigid_body([(str(k), _number(v, f"parameter `{k}`")) for k, v in parameters.items()])
        return body

    @property
    def name(self) -> str:
        """``rigid_body``, or the name given."""
        return str(self._rigid.name)

    @property
    def parameters(self) -> dict[str, float]:
        """The parameters, by name."""
        return dict(self._rigid.parameters)

    @property
    def symmetry(self) -> str:
        """The rotations of space that leave the Lagrangian invariant: ``SO(3)`` (all), ``vertical``
        (about e3) or ``none``."""
        return str(self._rigid.symmetry)

    @property
    def coordinates(self) -> list[str]:
        """The shape coordinates, in the order of ``q0`` and of a run's ``q`` (none for the built-in
        body); the attitude R is not among them."""
        return [name for name, _ in self._rigid.shape]

    @property
    def shape(self) -> list[str]:
        """The shape coordinates."""
        return self.coordinates

    @property
    def group(self) -> list[str]:
        """None: the group is SO(3) itself, acting on R."""
        return []

    @property
    def angles(self) -> list[str]:
        """The shape coordinates on the circle."""
        return [name for name, kind in self._rigid.shape if kind == "angle"]

    def __repr__(self) -> str:
        return f"ddirac.RigidBody({self.name!r}, shape={self.coordinates}, symmetry={self.symmetry!r})"


class RigidRun(Run):
    """The rows of a rigid body's run as NumPy arrays, and its summary.

    Attributes: ``t`` (rows,), ``R`` (rows, 3, 3: the attitude, body to space), ``Pi`` (rows, 3: the
    body angular momentum), ``energy``, ``momentum_map`` (rows, 3: the spatial angular momentum R Π),
    ``summary`` (the dict ``summary.json`` holds: ``final.R``, ``final.Pi``, ``casimir``,
    ``orthogonality``, ...), ``q`` and ``p`` (rows, shape coordinates: the shape and its momenta; no
    columns for the built-in body), ``coordinates`` (the shape's names); ``discrete_energy`` is NaN (not
    computed on SO(3)).
    """

    R: np.ndarray
    Pi: np.ndarray

    def __init__(self, arrays: Mapping[str, Any], shape: Sequence[str] = ()) -> None:
        rows = len(arrays["t"])
        super().__init__({"t": arrays["t"], "q": arrays["q"], "p": arrays["p"],
                          "energy": arrays["energy"], "discrete_energy": np.full(rows, np.nan),
                          "momentum_map": arrays["momentum_map"], "summary": arrays["summary"]},
                         shape, ["x", "y", "z"])
        self.R = arrays["R"]
        self.Pi = arrays["Pi"]

    def columns(self) -> dict[str, np.ndarray]:
        """The rows as named columns, as ``trajectory.csv`` names them: ``t``, ``R11`` … ``R33``,
        ``Pi1`` … ``Pi3``, the shape coordinates and ``p_<coordinate>``, ``energy``, ``momentum_x`` …
        ``momentum_z``."""
        out = {"t": self.t}
        out.update({f"R{i + 1}{j + 1}": self.R[:, i, j] for i in range(3) for j in range(3)})
        out.update({f"Pi{i + 1}": self.Pi[:, i] for i in range(3)})
        out.update({name: self.q[:, i] for i, name in enumerate(self.coordinates)})
        out.update({f"p_{name}": self.p[:, i] for i, name in enumerate(self.coordinates)})
        out["energy"] = self.energy
        out.update({f"momentum_{a}": self.momentum_map[:, i] for i, a in enumerate("xyz")})
        return out

    def to_pandas(self) -> pandas.DataFrame:
        """The named columns as a ``pandas.DataFrame`` (pandas is imported only here)."""
        import pandas

        return pandas.DataFrame(self.columns())

    def __repr__(self) -> str:
        return f"ddirac.RigidRun(rows={len(self)}, steps={self.summary['steps']}, step={self.summary['step']})"


def _attitude(R0: Any) -> list[list[float]]:
    array = np.asarray(R0, dtype=float)
    if array.shape != (3, 3):
        raise _ddirac.Error(f"`R0` must be a 3 × 3 rotation (body to space); it has the shape {array.shape}")
    return array.tolist()


def _three(values: Any, what: str) -> list[float]:
    array = np.asarray(values, dtype=float)
    if array.shape != (3,):
        raise _ddirac.Error(f"`{what}` must be 3 numbers (body frame); it has the shape {array.shape}")
    return array.tolist()


def simulate_rigid(body: RigidBody, R0: Any, Pi0: Optional[Sequence[float]], Omega0: Optional[Sequence[float]],
                   q0: Any, p0: Any, v0: Any, step: Optional[float], steps: Optional[int],
                   duration: Optional[float], every: int, keys: dict[str, Any], progress: Any) -> RigidRun:
    """A rigid body's run (see :func:`ddirac.simulate`), its warnings not yet emitted."""
    from .progress import callback
    from .run import _count, _vector, _whole

    if R0 is None:
        raise _ddirac.Error("a rigid body's run needs `R0`, the initial attitude (a 3 × 3 rotation, body to space)")
    h, n = _ddirac.time_grid(None if step is None else float(step), None if steps is None else _whole(steps, "steps"),
                             None if duration is None else float(duration))
    args = {"r0": _attitude(R0), "pi0": None if Pi0 is None else _three(Pi0, "Pi0"),
            "omega0": None if Omega0 is None else _three(Omega0, "Omega0"), "step": h, "steps": n, "duration": None,
            "method": keys}
    names = body.coordinates
    for key, value, velocities in (("q0", q0, False), ("p0", p0, False), ("v0", v0, True)):
        args[key] = None if value is None else _vector(value, names, key, velocities=velocities)
    every = _count(every, "every")
    reporter = callback(progress, n)
    try:
        arrays = _ddirac.simulate_rigid(body._rigid, args, every, reporter.report)
        reporter.done()
    finally:
        reporter.close()
    return RigidRun(arrays, body.coordinates)
