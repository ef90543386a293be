"""Spec files: :func:`load` reads a TOML spec as ``ddirac run`` does, with overrides as ``--set`` gives them."""

from __future__ import annotations

import json
import math
import os
import warnings
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np

from . import _ddirac
from .convergence import ConvergenceTable
from .progress import ProgressArgument
from .run import Run
from .run_warnings import warn_run
from .system import System

def load(spec: SpecLike, overrides: Optional[Mapping[str, Any]] = None) -> Spec:
    """Reads and validates the spec at the path ``spec``; ``overrides`` maps spec keys to values, as
    ``--set KEY=VALUE`` does: ``ddirac.load("spec.toml", overrides={"method.reduced": False,
    "time.steps": 1000, "initial.q.phi1": 2.0})``. Errors are :class:`ddirac.Error` with the
    diagnostic the command line prints (the spec line underlined).

    ``spec`` may also be a :class:`Spec` that :func:`load` returned: its file is read again with its
    own overrides and then ``overrides`` on top (a key given in both takes the value given here), as
    loading the file with both sets at once would.

    An override of ``time.duration`` that changes the step h (a spec that gives ``steps`` and
    ``duration`` keeps N, and so scales h) warns with the h that results."""
    assignments = [f"{key}={_toml(value, key)}" for key, value in (overrides or {}).items()]
    path, earlier = source(spec)
    assignments = earlier + assignments
    loaded = Spec(_ddirac.load_spec(path, assignments), path)
    loaded._assignments = assignments
    # What the overrides did that may surprise (the step h an override of another `[time]` key
    # gives), as `ddirac run` prints it.
    for note in loaded._handle.notes:
        warnings.warn(f"ddirac.load: {note}", UserWarning, stacklevel=2)
    return loaded


def source(spec: SpecLike) -> tuple[str, list[str]]:
    """The path of ``spec`` (a path or a :class:`Spec`) and its ``--set`` assignments, in order."""
    if isinstance(spec, Spec):
        return spec.path, list(spec._assignments)
    try:
        return os.fspath(spec), []
    except TypeError:
        raise _ddirac.Error(f"a spec is the path of a spec file or a ddirac.Spec from ddirac.load, "
                            f"not {type(spec).__name__}") from None


class Spec:
    """A validated spec: its system, time grid, initial data and method; :meth:`run` integrates it.

    Attributes: ``path`` (the spec file), ``system`` (a :class:`ddirac.System`), ``step``, ``steps``,
    ``q0``, ``p0`` or ``v0`` (the other None), ``method`` (the ``[method]`` keys, as a dict)."""

    path: str
    system: System
    step: float
    steps: int
    q0: np.ndarray
    p0: Optional[np.ndarray]
    v0: Optional[np.ndarray]
    method: dict[str, Any]

    def __init__(self, handle: _ddirac.LoadedSpec, path: str) -> None:
        from .system import System

        self._handle = handle
        self._assignments: list[str] = []
        self.path = path
        self.system = System._from_handle(handle.system)
        self.step, self.steps, q0, p0, v0 = handle.problem
        self.q0 = np.array(q0)
        self.p0 = None if p0 is None else np.array(p0)
        self.v0 = None if v0 is None else np.array(v0)
        self.method = handle.method

    @property
    def directory(self) -> str:
        """Where ``ddirac run`` would write this spec's output."""
        return os.fspath(self._handle.directory)

    def run(self, out: Optional[Union[str, os.PathLike[str]]] = None, write: Optional[bool] = None,
            progress: ProgressArgument = None) -> Run:
        """Integrates the spec and returns a :class:`ddirac.Run`.

        With ``out`` (a directory) or ``write=True`` (the spec's own directory) it also writes the files
        ``ddirac run`` writes there (trajectory, ``summary.json``, figures as the spec asks), staged and
        committed as a set, and the run's arrays are read back from them.

        The run's warnings (``summary["warnings"]``) are also emitted as :class:`ddirac.RunWarning`
        subclasses, as :func:`ddirac.simulate` emits them."""
        from .run import Run

        if out is None and not write:
            from .progress import callback

            reporter = callback(progress, self.steps)
            try:
                arrays = self._handle.run_arrays(reporter.report)
                reporter.done()
            finally:
                reporter.close()
            run = Run(arrays, self.system.coordinates, self.system.group)
        else:
            directory = os.fspath(self._handle.run_files(None if out is None else os.fspath(out)))
            run = _read_run(directory, self.system)
        warn_run(run.summary["warnings"])
        return run

    def check(self) -> dict[str, Any]:
        """:func:`ddirac.check` of this spec's system, initial data, time grid and method."""
        from .run import check

        method = {k: v for k, v in self.method.items() if k not in ("rule", "variant", "reduced")}
        return check(self.system, self.q0, p0=self.p0, v0=self.v0, step=self.step, steps=self.steps,
                     rule=self.method["rule"], variant=self.method["variant"], reduced=self.method["reduced"],
                     **method)

    def convergence(self, steps: Sequence[int]) -> ConvergenceTable:
        """:func:`ddirac.convergence` of this spec over its duration with the step counts ``steps``."""
        from .convergence import convergence

        method = dict(self.method)
        return convergence(self.system, steps, self.step * self.steps, self.q0, p0=self.p0, v0=self.v0, **method)

    def __repr__(self) -> str:
        return f"ddirac.Spec({self.path!r}, system={self.system.name!r}, steps={self.steps}, step={self.step})"


#: What takes a spec: the path of a spec file, or a :class:`Spec` from :func:`load` (its file with its
#: overrides).
SpecLike = Union[str, os.PathLike[str], Spec]


def _read_run(directory: str, system: System) -> Run:
    """The arrays of a run directory (trajectory.csv, or npy/), as a Run."""
    from .run import Run

    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    names = system.coordinates
    csv = os.path.join(directory, "trajectory.csv")
    if os.path.exists(csv):
        data = np.genfromtxt(csv, delimiter=",", names=True, dtype=float, missing_values="", filling_values=np.nan)
        header = data.dtype.names or ()

        def column(name: str) -> np.ndarray:
            return np.atleast_1d(data[name])
    else:
        header = tuple(f[:-4] for f in os.listdir(os.path.join(directory, "npy")) if f.endswith(".npy"))

        def column(name: str) -> np.ndarray:
            return np.load(os.path.join(directory, "npy", f"{name}.npy"))
    arrays: dict[str, Any] = {
        "t": column("t"),
        "q": np.column_stack([column(n) for n in names]),
        "p": np.column_stack([column(f"p_{n}") for n in names]),
        "energy": column("energy"),
        "discrete_energy": column("discrete_energy"),
        "momentum_map": np.column_stack([column(f"momentum_{g}") for g in system.group])
        if system.group else np.empty((len(column("t")), 0)),
        "summary": summary,
        # The files have a `chart` column when the run can switch charts.
        "switching": "chart" in header,
    }
    if arrays["switching"]:
        arrays["chart"] = column("chart").astype(np.int64)
    return Run(arrays, names, system.group)


def _toml(value: Any, key: str) -> str:
    """A Python value as a TOML value for ``--set``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_toml(v, key)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml(v, key) for v in value) + "]"
    raise _ddirac.Error(f"override `{key}`: a {type(value).__name__} is not a spec value")
