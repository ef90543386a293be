"""ddirac: structure-preserving simulation of mechanical systems with symmetry.

Discrete Lagrange–Dirac systems, their reduction by an abelian symmetry to the discrete
Lagrange–Poincaré–Dirac equations, and the reconstruction of the group motion, from NumPy::

    import ddirac
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    run = ddirac.simulate(dsp, q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=10_000,
                          rule="midpoint", reduced=True)
    run.t, run.q, run.p, run.energy, run.discrete_energy, run.momentum_map   # NumPy arrays
    run.summary                                                              # the dict of summary.json

Many runs of one spec that differ in initial data or parameters run in parallel, locally or on a Dask
cluster: ``ddirac.ensemble("spec.toml", members={"initial.q.phi1": np.linspace(1, 2, 100)})``.

A spec file runs as ``ddirac run`` runs it: ``ddirac.load("spec.toml", overrides={"method.reduced":
False}).run()``. Every error is a :class:`ddirac.Error` whose message names the argument and the cause;
its subclasses :class:`SpecError`, :class:`ExpressionError` (``origin``, ``text``, ``span``),
:class:`InvarianceError` and :class:`ConvergenceError` (``step``, ``t``, ``h``, ``residual``) say more.

A run that completes with warnings (``run.summary["warnings"]``) also emits them through the
:mod:`warnings` module as :class:`ddirac.RunWarning` subclasses, one per kind (:class:`EnergyJumpWarning`,
:class:`SubdividedWarning`, ...): ``warnings.simplefilter("error", ddirac.RunWarning)`` turns a warned run
into an exception, ``warnings.simplefilter("ignore", ddirac.SubdividedWarning)`` silences one kind.
"""

from ._ddirac import ConvergenceError, Error, ExpressionError, InvarianceError, SpecError, __version__
from .system import System, builtin_systems
from .convergence import ConvergenceTable, convergence
from .ensembles import EnsembleResult, ensemble
from .equilibria import RelativeEquilibrium, RelativeEquilibriumFamily, relative_equilibria, relative_equilibrium_family
from .run import Run, check, simulate
from .rigid import RigidBody, RigidRun
from .run_warnings import (
    EnergyDriftWarning, EnergyJumpWarning, InvarianceUndecidedWarning, LooseToleranceWarning,
    NewtonFallbackWarning, NoEnergyWarning, NotInvariantWarning, RunWarning, SensitivityLostWarning,
    SingularChartWarning, SubdividedWarning, UnderResolvedWarning,
)
from .spec import Spec, load

__all__ = [
    "ConvergenceError", "ConvergenceTable", "EnsembleResult", "Error", "ExpressionError", "InvarianceError", "Run",
    "RigidBody", "RigidRun", "RelativeEquilibrium", "relative_equilibria",
    "RelativeEquilibriumFamily", "relative_equilibrium_family",
    "Spec", "SpecError", "System", "builtin_systems", "check", "convergence", "ensemble", "load", "simulate", "__version__",
    "RunWarning", "EnergyDriftWarning", "EnergyJumpWarning", "InvarianceUndecidedWarning",
    "LooseToleranceWarning", "NewtonFallbackWarning", "NoEnergyWarning", "NotInvariantWarning", "SensitivityLostWarning",
    "SingularChartWarning", "SubdividedWarning", "UnderResolvedWarning",
]
