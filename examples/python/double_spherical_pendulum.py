"""The double spherical pendulum of the paper (§7.2) from Python: reduced and unreduced runs, the
discrete energy L_d of both and their difference, and the path of the second bob, with Matplotlib.

    pip install . matplotlib      # from the repository's root
    python examples/python/double_spherical_pendulum.py [--out DIR]   # writes DIR/double_spherical_pendulum.png

The figure goes into the directory ``--out`` (default ``out``, made if missing); the script prints its path.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import ddirac  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="out", help="the directory of the figure (default: out)")
args = parser.parse_args()
figure = Path(args.out) / "double_spherical_pendulum.png"

dsp = ddirac.System.builtin("double_spherical_pendulum")
common = dict(q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=10_000, rule="midpoint")
reduced = ddirac.simulate(dsp, reduced=True, **common)
unreduced = ddirac.simulate(dsp, reduced=False, **common)
print(reduced.summary["derivatives"])
print("largest |q_reduced − q_unreduced|:", np.max(np.abs(reduced.q - unreduced.q)))
print("momentum map drift (reduced):", reduced.summary["momentum_map"]["max_drift"])

p = dsp.parameters
vartheta1, phi1, vartheta2, phi2 = reduced.q.T
theta1, theta2 = vartheta1 - vartheta2, vartheta1 + vartheta2
x = p["l1"] * np.sin(phi1) * np.cos(theta1) + p["l2"] * np.sin(phi2) * np.cos(theta2)
y = p["l1"] * np.sin(phi1) * np.sin(theta1) + p["l2"] * np.sin(phi2) * np.sin(theta2)

fig, axes = plt.subplots(2, 2, figsize=(12, 8))
axes[0, 0].plot(reduced.t, phi1)
axes[0, 0].set(xlabel="t", ylabel="φ₁", title="φ₁(t), reduced")
axes[0, 1].plot(reduced.t[:-1], reduced.discrete_energy[:-1], label="reduced")
axes[0, 1].plot(unreduced.t[:-1], unreduced.discrete_energy[:-1], "--", label="unreduced")
axes[0, 1].set(xlabel="t", ylabel="L_d(q_k, q_k+1)", title="discrete energy")
axes[0, 1].legend()
axes[1, 0].plot(reduced.t[:-1], reduced.discrete_energy[:-1] - unreduced.discrete_energy[:-1])
axes[1, 0].set(xlabel="t", ylabel="difference", title="L_d reduced − L_d unreduced")
axes[1, 1].plot(x, y, lw=0.5)
axes[1, 1].set(xlabel="x", ylabel="y", title="second bob, projection on the (x, y) plane", aspect="equal")
fig.tight_layout()
figure.parent.mkdir(parents=True, exist_ok=True)
fig.savefig(figure, dpi=120)
print(f"wrote {figure}")
