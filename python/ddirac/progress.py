"""Progress of a run: a tqdm bar when tqdm is installed, else one line on stderr redrawn in place.

On by default in a notebook (an IPython kernel), off in scripts; ``progress=True`` or ``False`` chooses,
and a callable ``progress(k, steps)`` receives the step index instead. The engine reports about ten
times a second; a run that completes reports ``k = steps`` last, however short it was (a run shorter
than a tenth of a second reports only that).
"""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Union

#: What the ``progress`` argument of a run takes: None (a bar in a notebook only), a bool, or a
#: callable ``progress(k, total)``.
ProgressArgument = Union[None, bool, Callable[[int, int], Any]]


def in_notebook() -> bool:
    """Whether the code runs in a Jupyter kernel."""
    shell = sys.modules.get("IPython")
    if shell is None:
        return False
    try:
        return type(shell.get_ipython()).__name__ == "ZMQInteractiveShell"  # type: ignore[attr-defined]
    except Exception:  # an IPython without a running shell
        return False


class Bar:
    """A progress bar over ``steps`` steps; ``update(k)`` moves it, ``close()`` ends it."""

    def __init__(self, steps: int, description: str = "ddirac", unit: str = "step") -> None:
        self.steps = steps
        self._tqdm: Any
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self._tqdm = None
        else:
            self._tqdm = tqdm(total=steps, desc=description, unit=unit, leave=False)
        self._shown = False

    def update(self, k: int) -> None:
        if self._tqdm is not None:
            self._tqdm.update(k - self._tqdm.n)
            return
        done = k / self.steps if self.steps else 1.0
        width = 30
        sys.stderr.write(f"\rddirac [{'#' * int(done * width):<{width}}] {100 * done:5.1f}% {k}/{self.steps}")
        sys.stderr.flush()
        self._shown = True

    def close(self) -> None:
        if self._tqdm is not None:
            self._tqdm.close()
        elif self._shown:
            sys.stderr.write("\r" + " " * 70 + "\r")
            sys.stderr.flush()


class Reporter:
    """The progress of one call: :attr:`report` is the engine's callback ``f(k)`` (None without
    progress), :meth:`done` reports completion (``k = total``, unless the engine's last report was
    that already), :meth:`close` ends a bar (call it in ``finally``)."""

    def __init__(self, report: Optional[Callable[[int], Any]], total: int,
                 close: Optional[Callable[[], None]] = None) -> None:
        self.total = total
        self._report = report
        self._close = close
        self._last: Optional[int] = None
        self.report: Optional[Callable[[int], None]] = None if report is None else self._forward

    def _forward(self, k: int) -> None:
        self._last = k
        assert self._report is not None
        self._report(k)

    def done(self) -> None:
        if self._report is not None and self._last != self.total:
            self._forward(self.total)

    def close(self) -> None:
        if self._close is not None:
            self._close()


def callback(progress: ProgressArgument, steps: int, unit: str = "step") -> Reporter:
    """The :class:`Reporter` of the ``progress`` argument; ``steps`` counts ``unit`` items (steps of a
    run, members of an ensemble)."""
    if progress is None:
        progress = in_notebook()
    if progress is False:
        return Reporter(None, steps)
    if callable(progress) and progress is not True:
        user = progress
        return Reporter(lambda k: user(k, steps), steps)
    bar = Bar(steps, unit=unit)
    return Reporter(bar.update, steps, bar.close)
