#!/usr/bin/env python3
"""error/h² of the spherical pendulum's final bob over a sweep of step counts, against a fine run.

    scripts/atlas_sweep.py BINARY [--set KEY=VALUE ...] [--duration T] N1 N2 ...

Runs `examples/spherical_pendulum.toml` with `time.steps = N` (and `time.duration = T`, default 20) in place
of its step, with the overrides given, and prints for each N the distance of the final bob (a unit vector)
from that of the same run at 64 000 steps, divided by h², with the chart switches and the warnings. Used in
BENCHMARKS.md ("The atlas's error in h").
"""

import argparse
import json
import math
import os
import re
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPEC = os.path.join(ROOT, "examples", "spherical_pendulum.toml")


def run(binary, steps, duration, sets):
    with tempfile.TemporaryDirectory() as directory:
        text = open(SPEC).read()
        text = re.sub(r"^step = .*$", f"steps = {steps}", text, flags=re.M)
        text = re.sub(r"^duration = .*$", f"duration = {duration}", text, flags=re.M)
        spec = os.path.join(directory, "spec.toml")
        with open(spec, "w") as f:
            f.write(text)
        out = os.path.join(directory, "out")
        arguments = [binary, "run", spec, "--out", out, "--quiet"]
        for s in sets:
            arguments += ["--set", s]
        subprocess.run(arguments, check=True, capture_output=True)
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)


def bob(summary):
    q = dict(zip(summary["coordinates"], summary["final"]["q"]))
    theta, phi = q["theta"], q["phi"]
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), -math.cos(theta))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("steps", type=int, nargs="+")
    parser.add_argument("--set", action="append", default=[], dest="sets")
    parser.add_argument("--duration", type=float, default=20.0)
    args = parser.parse_args()
    reference = bob(run(args.binary, 64000, args.duration, args.sets))
    for steps in args.steps:
        h = args.duration / steps
        summary = run(args.binary, steps, args.duration, args.sets)
        error = math.dist(bob(summary), reference)
        kinds = [w["kind"] for w in summary["warnings"]]
        print(f"N = {steps:6}  h = {h:.6f}  error = {error:.3e}  error/h² = {error / h / h:8.1f}  "
              f"switches = {summary['chart_switches']}  warnings = {kinds}")


if __name__ == "__main__":
    main()
