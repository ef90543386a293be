"""Progress of a run: a tqdm bar when tqdm is installed, else one line on stderr redrawn in place.

On by default in a notebook (an IPython kernel), off in scripts; ``progress=True`` or ``False`` chooses,
and a callable ``progress(k, steps)`` receives the step index instead. The engine reports about ten
times a second; a run shorter than that shows no bar.
"""

import sys


def in_notebook():
    """Whether the code runs in a Jupyter kernel."""
    shell = sys.modules.get("IPython")
    if shell is None:
        return False
    try:
        return type(shell.get_ipython()).__name__ == "ZMQInteractiveShell"
    except Exception:  # an IPython without a running shell
        return False


class Bar:
    """A progress bar over ``steps`` steps; ``update(k)`` moves it, ``close()`` ends it."""

    def __init__(self, steps, description="ddirac", unit="step"):
        self.steps = steps
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self._tqdm = None
        else:
            self._tqdm = tqdm(total=steps, desc=description, unit=unit, leave=False)
        self._shown = False

    def update(self, k):
        if self._tqdm is not None:
            self._tqdm.update(k - self._tqdm.n)
            return
        done = k / self.steps if self.steps else 1.0
        width = 30
        sys.stderr.write(f"\rddirac [{'#' * int(done * width):<{width}}] {100 * done:5.1f}% {k}/{self.steps}")
        sys.stderr.flush()
        self._shown = True

    def close(self):
        if self._tqdm is not None:
            self._tqdm.close()
        elif self._shown:
            sys.stderr.write("\r" + " " * 70 + "\r")
            sys.stderr.flush()


def callback(progress, steps, unit="step"):
    """The engine's callback ``f(k)`` and a closer for the ``progress`` argument, or (None, None);
    ``steps`` counts ``unit`` items (steps of a run, members of an ensemble)."""
    if progress is None:
        progress = in_notebook()
    if progress is False:
        return None, None
    if callable(progress) and progress is not True:
        return (lambda k: progress(k, steps)), None
    bar = Bar(steps, unit=unit)
    return bar.update, bar.close
