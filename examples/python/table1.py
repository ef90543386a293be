"""The paper's Table 1 from Python: the charged particle in a constant magnetic field (§7.1), T = 20,
reduced (+) and (−) equations with the left rule, the error ‖q(T) − q_N‖ against the exact gyration.

    pip install .            # from the repository's root
    python examples/python/table1.py
"""

import ddirac

PRINTED = {10: 1.6781, 50: 0.25971, 100: 0.06626, 200: 0.01664}

particle = ddirac.System.builtin("charged_particle")
print(f"{'N':>5} {'(+) reduced':>14} {'(−) reduced':>14} {'unreduced (+)':>14} {'paper':>9}")
for steps, printed in PRINTED.items():
    errors = []
    for variant, reduced in [("plus", True), ("minus", True), ("plus", False)]:
        run = ddirac.simulate(particle, q0=[0, 0, 0, 0], p0=[1, 0, 1, 1], steps=steps, duration=20.0, rule="left",
                              variant=variant, reduced=reduced)
        errors.append(run.summary["reference_error"])
    print(f"{steps:>5} " + " ".join(f"{e:>14.5g}" for e in errors) + f" {printed:>9}")
