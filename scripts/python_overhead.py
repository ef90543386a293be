#!/usr/bin/env python3
"""What a run costs from Python against the same run in the Rust library, side by side in one process.

    pip install .  &&  python3 scripts/python_overhead.py [--rounds 15]

Each round times `ddirac.simulate` (the wall time of the call: argument checks, set-up, integration,
rows into NumPy arrays, the summary dict) and the same run made inside Rust by the module
(`_ddirac.rust_seconds`: set-up, integration, rows into vectors), in alternating order, and forms the
ratio (or the difference) within the round; the median and the interquartile range over the rounds are
printed. Cases: the double spherical pendulum, 10⁴ reduced midpoint steps (the README's main job),
and a run of 10 steps (the fixed cost of a call).
"""

import argparse
import statistics
import time

import ddirac
from ddirac import _ddirac
from ddirac.run import _prepare


def quartiles(values):
    q = statistics.quantiles(values, n=4)
    return f"{statistics.median(values):.4g} [IQR {q[0]:.4g} – {q[2]:.4g}]"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=15)
    args = parser.parse_args()
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    for steps, what in [(10_000, "ratio"), (10, "difference")]:
        kwargs = dict(q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=steps, rule="midpoint", reduced=True)
        run_args = _prepare(dsp, kwargs["q0"], kwargs["p0"], None, 0.01, steps, None, "midpoint", "plus", True, {})
        python, rust, compared = [], [], []
        for r in range(args.rounds):
            times = {}
            for side in (("python", "rust") if r % 2 == 0 else ("rust", "python")):
                if side == "python":
                    start = time.perf_counter()
                    ddirac.simulate(dsp, **kwargs)
                    times[side] = time.perf_counter() - start
                else:
                    times[side] = _ddirac.rust_seconds(dsp._handle, run_args)
            python.append(times["python"])
            rust.append(times["rust"])
            compared.append(times["python"] / times["rust"] if what == "ratio" else
                            (times["python"] - times["rust"]) * 1e6)
        print(f"double spherical pendulum, {steps} steps: Python {quartiles([t * 1e3 for t in python])} ms, "
              f"Rust {quartiles([t * 1e3 for t in rust])} ms")
        unit = "Python ÷ Rust" if what == "ratio" else "Python − Rust (µs)"
        print(f"  {unit}: {quartiles(compared)}")


if __name__ == "__main__":
    main()
