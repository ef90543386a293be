"""Ensembles: many runs of one spec that differ in initial data and/or parameters, on local threads
or on the workers of a Dask cluster (:func:`ensemble`)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _ddirac
from .progress import ProgressArgument
from .run_warnings import warn_members
from .spec import SpecLike

if TYPE_CHECKING:  # optional: imported by the functions that need it
    import pandas

#: Per-member diagnostics, as ``ddirac ensemble`` names its arrays (NaN for a failed member).
DIAGNOSTICS = (
    "energy_error",            # max |H_k - H_0| over the reported rows
    "energy_relative_error",   # energy_error / |H_0|
    "momentum_map_drift",      # max |J_k - J_0| over all steps
    "newton_iterations",       # Newton corrections over all steps
    "newton_max_iterations",   # largest number of corrections in one step
    "newton_max_residual",     # largest accepted residual norm
    "reference_error",         # |q(T) - q_N| against the exact solution, where the system has one
)


class EnsembleResult:
    """The results of an ensemble, arrays with a leading member axis.

    ``final_q``, ``final_p`` (members × n: q_N and p_N, or the state of the failed step; of a rigid body
    its shape coordinates and momenta, members × 0 for a body without shape), for a rigid body
    ``final_R`` (members × 3 × 3) and ``final_Pi`` (members × 3) (``attitude`` is True; None otherwise),
    ``status`` (``"ok"`` or ``"failed"`` per member), ``steps`` (steps taken), ``diagnostics`` (a dict
    of arrays, :data:`DIAGNOSTICS`), ``failures`` (a list of dicts ``member``, ``step``, ``t``,
    ``error``), ``members`` (a dict of the varied values by key), ``coordinates``, ``warnings`` (a dict:
    warning kind → the number of members whose run had it), ``derivatives`` (the derivative path → the
    number of members that took it); with trajectories
    ``t`` (rows), ``q`` and ``p`` (members × rows × n) and ``energy`` (members × rows), for a rigid body
    also ``R`` (members × rows × 3 × 3) and ``Pi`` (members × rows × 3), NaN after a failed member's last
    row.
    """

    coordinates: list[str]
    keys: list[str]
    members: dict[str, np.ndarray]
    attitude: bool
    final_q: np.ndarray
    final_p: np.ndarray
    final_R: Optional[np.ndarray]
    final_Pi: Optional[np.ndarray]
    status: np.ndarray
    steps: np.ndarray
    diagnostics: dict[str, np.ndarray]
    failures: list[dict[str, Any]]
    derivatives: dict[str, int]
    warnings: dict[str, int]
    member_seconds: float
    t: np.ndarray
    q: np.ndarray
    p: np.ndarray
    energy: np.ndarray
    R: Optional[np.ndarray]
    Pi: Optional[np.ndarray]

    def __init__(self, parts: Sequence[Mapping[str, Any]]) -> None:
        first = parts[0]
        self.coordinates = list(first["coordinates"])
        self.keys = list(first["keys"])

        def cat(name: str) -> np.ndarray:
            return np.concatenate([p[name] for p in parts])
        values = cat("members")
        self.members = {key: values[:, i] for i, key in enumerate(self.keys)}
        self.attitude = bool(first.get("attitude", False))
        count = sum(len(p["finished"]) for p in parts)

        def state(name: str, rows: tuple[int, ...] = ()) -> np.ndarray:
            # A body without shape coordinates has no q, p: members × (rows ×) 0.
            return cat(name) if name in first else np.empty((count, *rows, 0))
        self.final_q = state("final_q")
        self.final_p = state("final_p")
        self.final_R = cat("final_R") if self.attitude else None
        self.final_Pi = cat("final_Pi") if self.attitude else None
        finished = cat("finished")
        self.status = np.where(finished, "ok", "failed")
        self.steps = cat("steps")
        self.diagnostics = {name: np.concatenate([p["diagnostics"][name] for p in parts]) for name in DIAGNOSTICS}
        self.failures = [f for p in parts for f in p["failures"]]
        self.derivatives = _sum_counts(p["derivatives"] for p in parts)
        self.warnings = _sum_counts(p["warnings"] for p in parts)
        self.member_seconds = sum(p["member_seconds"] for p in parts)
        self.R = self.Pi = None
        if "energy" in first:
            self.t = first["t"]
            rows = (len(self.t),)
            self.q = state("q", rows)
            self.p = state("p", rows)
            self.energy = cat("energy")
            if self.attitude:
                self.R = cat("R")
                self.Pi = cat("Pi")

    def __len__(self) -> int:
        return len(self.status)

    def __repr__(self) -> str:
        failed = int(np.sum(self.status == "failed"))
        return f"ddirac.EnsembleResult(members={len(self)}, failed={failed}, coordinates={self.coordinates})"

    def columns(self) -> dict[str, np.ndarray]:
        """The final table as ``final.csv`` has it: ``member``, ``status``, for a rigid body ``R11`` …
        ``R33`` and ``Pi1`` … ``Pi3``, each coordinate, ``p_<coordinate>``, then the diagnostics."""
        out = {"member": np.arange(len(self)), "status": self.status}
        if self.final_R is not None and self.final_Pi is not None:
            out.update({f"R{i + 1}{j + 1}": self.final_R[:, i, j] for i in range(3) for j in range(3)})
            out.update({f"Pi{i + 1}": self.final_Pi[:, i] for i in range(3)})
        out.update({name: self.final_q[:, i] for i, name in enumerate(self.coordinates)})
        out.update({f"p_{name}": self.final_p[:, i] for i, name in enumerate(self.coordinates)})
        out.update(self.diagnostics)
        return out

    def to_pandas(self) -> pandas.DataFrame:
        """:meth:`columns` as a ``pandas.DataFrame`` (pandas is imported only here)."""
        import pandas

        return pandas.DataFrame(self.columns())


def _sum_counts(lists: Iterable[Iterable[tuple[str, int]]]) -> dict[str, int]:
    total: dict[str, int] = {}
    for pairs in lists:
        for key, count in pairs:
            total[key] = total.get(key, 0) + count
    return total


def _source(spec: SpecLike) -> tuple[str, str, list[str]]:
    """(path, text, --set assignments) of a spec path or a :class:`ddirac.Spec`."""
    from .spec import source

    path, assignments = source(spec)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return path, text, assignments


def _columns(members: Any) -> list[tuple[str, list[float]]]:
    """Members (a dict of equal-length arrays or a pandas DataFrame) as a list of (key, values)."""
    if hasattr(members, "columns") and hasattr(members, "to_numpy"):  # a DataFrame
        items = [(str(c), members[c].to_numpy()) for c in members.columns]
    elif isinstance(members, dict):
        items = [(str(k), v) for k, v in members.items()]
    else:
        raise _ddirac.Error("`members` is a dict of equal-length arrays keyed by spec keys, or a pandas DataFrame")
    columns = []
    for key, values in items:
        array = np.asarray(values, dtype=float)
        if array.ndim != 1:
            raise _ddirac.Error(f"the members of `{key}` are not a 1-d array (shape {array.shape})")
        columns.append((key, array.tolist()))
    return columns


def _chunks(count: int, parts: int) -> list[tuple[int, int]]:
    """``parts`` contiguous ranges of ``range(count)``, as ``ddirac ensemble --shard`` cuts them."""
    return [(i * count // parts, (i + 1) * count // parts) for i in range(parts) if i * count // parts < (i + 1) * count // parts]


def _run_chunk(path: str, text: str, assignments: list[str], columns: list[tuple[str, list[float]]], offset: int,
               threads: Optional[int], trajectories: Optional[bool]) -> dict[str, Any]:
    """One Dask task: the members ``columns`` (numbered from ``offset``) on this worker."""
    from . import _ddirac as core

    return core.ensemble(path, text, assignments, columns, offset, threads, trajectories, None)


def ensemble(spec: SpecLike, members: Union[Mapping[str, Any], pandas.DataFrame, None] = None, client: Any = None,
             threads: Optional[int] = None, trajectories: Optional[bool] = None, chunks: Optional[int] = None,
             progress: ProgressArgument = None) -> EnsembleResult:
    """Runs the members of ``spec`` (a spec path or a :class:`ddirac.Spec` from :func:`ddirac.load`) and
    returns an :class:`EnsembleResult`.

    ``members`` is a dict of equal-length arrays keyed as ``--set`` names the values
    (``initial.q.<coordinate>``, ``initial.p.<coordinate>``, ``initial.v.<coordinate>``,
    ``parameters.<name>``; for a rigid body also ``initial.Pi.<i>`` and ``initial.Omega.<i>``, i = 1, 2,
    3), or a pandas DataFrame with those columns; without it the spec's
    ``[ensemble]`` table generates them. Member k equals the single run of the spec with its values
    set, bit for bit. A member that fails is recorded (``status``, ``failures``) and the others go on.

    Without ``client`` the members run on ``threads`` local threads (default: all cores) with the GIL
    released, with a progress bar (``progress=True``; by default only in a notebook) or a callback
    ``progress(done, members)`` called about twenty times a second.
    With a ``dask.distributed.Client`` they are cut into ``chunks`` contiguous parts (default: four per
    worker thread), each a task that runs the Rust core on a worker (one thread per task, the GIL
    released), and the parts come back as the same arrays, bit for bit equal to the local run; a chunk
    whose worker dies is run again elsewhere by Dask. ``trajectories=True`` also returns every member's
    rows (at the spec's ``output.every``); the default is the spec's ``[ensemble] trajectories``.

    The members' warnings are emitted once per kind as :class:`ddirac.RunWarning` subclasses, each with
    the number of members that had it (``count``; ``EnsembleResult.warnings`` holds these numbers).
    """
    path, text, assignments = _source(spec)
    if members is None:
        keys, values = _ddirac.ensemble_members(path, text, assignments)
        columns = [(key, values[:, i].tolist()) for i, key in enumerate(keys)]
    else:
        columns = _columns(members)
    if client is None:
        from .progress import callback

        reporter = callback(progress, len(columns[0][1]) if columns else 0, unit="member")
        try:
            parts = [_ddirac.ensemble(path, text, assignments, columns, 0, threads, trajectories, reporter.report)]
            reporter.done()
        finally:
            reporter.close()
        return _warned(EnsembleResult(parts))
    count = len(columns[0][1]) if columns else 0
    if count == 0:
        raise _ddirac.Error("the ensemble has no members")
    if chunks is None:
        workers = client.scheduler_info().get("workers", {})
        slots = sum(w.get("nthreads", 1) for w in workers.values()) or 1
        chunks = 4 * slots
    futures: list[Any] = []
    for start, end in _chunks(count, max(1, min(int(chunks), count))):
        part = [(key, values[start:end]) for key, values in columns]
        futures.append(client.submit(_run_chunk, path, text, assignments, part, start, 1, trajectories,
                                     key=f"ddirac-ensemble-{os.getpid()}-{id(futures)}-{start}"))
    parts = client.gather(futures)
    return _warned(EnsembleResult(parts))


def _warned(result: EnsembleResult) -> EnsembleResult:
    """``result``, its warnings emitted: one per kind, with the number of members that had it."""
    warn_members(result.warnings, len(result))
    return result
