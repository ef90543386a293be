#!/usr/bin/env python3
"""Two builds of `ddirac` side by side: time per step and compile set-up on the same runs.

    scripts/compare_binaries.py OLD_BINARY NEW_BINARY [--rounds R] [--callgrind]

Each case is run by both binaries in alternation, R rounds, the order swapped every round; a round's
ratio new ÷ old is formed within the round, and the median with the interquartile range over the rounds
is printed (the machine's load moves both alike). Time per step is the difference of the
`wall_seconds` (summary.json) of runs of 2N and N steps, divided by N, so that set-up cancels; set-up is the whole process's time of a one-step run with
compiled derivatives minus that of a one-step run with dual numbers. With `--callgrind`, each
per-step case is also counted in instructions per step under valgrind (the difference of runs of N
and 2N steps, repeatable on a loaded machine).
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def chain(links):
    """`--set` arguments for the built-in chain of `links` pendula, bent into one arch."""
    import math

    q = [round(0.5 * math.sin(math.pi * i / (links + 1)), 6) for i in range(1, links + 1)]
    return [
        "--set", f"parameters.links={links}",
        "--set", f"initial.q={q}",
        "--set", f"initial.p={[0.0] * links}",
    ]


EXAMPLES = os.path.join(ROOT, "examples")
# name, spec, extra arguments, steps
PER_STEP = [
    ("double spherical pendulum, reduced (+), compiled Newton", "double_spherical_pendulum.toml",
     ["--set", "method.derivatives=\"compiled\""], 100000),
    ("charged particle, reduced (+), closed-form step", "charged_particle.toml",
     ["--set", "method.derivatives=\"compiled\""], 1000000),
    ("chain of 8, midpoint, compiled Newton", "pendulum_chain.toml",
     ["--set", "method.derivatives=\"compiled\""] + chain(8), 100000),
    ("chain of 32, midpoint, compiled Newton", "pendulum_chain.toml",
     ["--set", "method.derivatives=\"compiled\""] + chain(32), 10000),
]
SET_UP = [
    ("spherical pendulum (text)", "spherical_pendulum.toml", []),
    ("chain of 50", "pendulum_chain.toml", chain(50)),
]


def steps_arguments(spec, steps):
    """`--set` arguments for `steps` steps of the spec's step size (given, or duration ÷ steps)."""
    with open(os.path.join(EXAMPLES, spec), "rb") as f:
        times = tomllib.load(f)["time"]
    step = times.get("step") or times["duration"] / times["steps"]
    return ["--set", f"time.steps={steps}", "--set", f"time.duration={steps * step!r}"]


def run(binary, spec, extra, steps):
    """Runs one spec; returns (summary, whole process seconds)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        args = [binary, "run", os.path.join(EXAMPLES, spec), "--out", out, *steps_arguments(spec, steps),
                "--set", "output.every=100000000", *extra]
        start = time.perf_counter()
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        seconds = time.perf_counter() - start
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f), seconds


def instructions(binary, spec, extra, steps):
    with tempfile.TemporaryDirectory() as tmp:
        log = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/cg", binary, "run",
             os.path.join(EXAMPLES, spec), "--out", f"{tmp}/out", *steps_arguments(spec, steps),
             "--set", "output.every=100000000", *extra],
            check=True, capture_output=True, text=True).stderr
        return next(int(line.split()[-1].replace(",", "")) for line in log.splitlines() if "Collected" in line)


def summarize(values):
    q = statistics.quantiles(values, n=4) if len(values) > 1 else [values[0]] * 3
    return f"{statistics.median(values):.4g} [IQR {q[0]:.4g} – {q[2]:.4g}]"


def side_by_side(rounds, measure):
    """Alternates old and new for `rounds` rounds; returns the old and new values and the ratios."""
    old, new, ratios = [], [], []
    for r in range(rounds):
        order = ("old", "new") if r % 2 == 0 else ("new", "old")
        got = {which: measure(which) for which in order}
        old.append(got["old"])
        new.append(got["new"])
        ratios.append(got["new"] / got["old"])
    return old, new, ratios


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--callgrind", action="store_true")
    args = parser.parse_args()
    binaries = {"old": os.path.abspath(args.old), "new": os.path.abspath(args.new)}

    print("time per step (ns), median over rounds [IQR]; ratio new ÷ old formed per round")
    for name, spec, extra, steps in PER_STEP:
        def per_step(which):
            once = run(binaries[which], spec, extra, steps)[0]["wall_seconds"]
            twice = run(binaries[which], spec, extra, 2 * steps)[0]["wall_seconds"]
            return (twice - once) / steps * 1e9
        old, new, ratios = side_by_side(args.rounds, per_step)
        print(f"  {name} ({steps} steps): old {summarize(old)}, new {summarize(new)}, "
              f"new ÷ old {summarize(ratios)}")
        if args.callgrind:
            n = max(steps // 10, 100)
            per = {which: (instructions(b, spec, extra, 2 * n) - instructions(b, spec, extra, n)) / n
                   for which, b in binaries.items()}
            print(f"    instructions per step: old {per['old']:.0f}, new {per['new']:.0f} "
                  f"({per['new'] / per['old']:.3f}×)")

    print("compile set-up (ms): one step compiled minus one step with dual numbers, whole process")
    for name, spec, extra in SET_UP:
        def set_up(which):
            compiled = run(binaries[which], spec, extra + ["--set", "method.derivatives=\"compiled\""], 1)[1]
            dual = run(binaries[which], spec, extra + ["--set", "method.derivatives=\"dual\""], 1)[1]
            return (compiled - dual) * 1e3
        old, new, ratios = side_by_side(args.rounds, set_up)
        print(f"  {name}: old {summarize(old)}, new {summarize(new)}, new ÷ old {summarize(ratios)}")


if __name__ == "__main__":
    main()
