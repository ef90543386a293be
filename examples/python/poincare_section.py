"""A Poincaré section of a charged particle in a magnetic mirror (examples/magnetic_mirror.toml) from
an ensemble of a few hundred members on one energy level.

Reduced by the rotations about the axis, the particle moves in the meridional plane (r, z) with
p_phi fixed: two degrees of freedom, so the crossings of the midplane z = 0 (upwards) of an orbit on
one energy level lie on a curve when the motion is regular (an adiabatic invariant holds) and fill
an area when it is chaotic. One call runs all members in parallel (the GIL released); each member
equals the single run of the spec with its initial data, bit for bit.

    pip install .  matplotlib        # from the repository's root
    python examples/python/poincare_section.py [--members 300] [--out DIR]   # writes DIR/poincare_section.png
    python examples/python/poincare_section.py --dask        # the same on a local Dask cluster
"""

import argparse
import time
from pathlib import Path

import numpy as np

import ddirac

SPEC = Path(__file__).resolve().parents[1] / "magnetic_mirror.toml"


def members_on_energy_level(spec, energy, count):
    """Initial data at the midplane z = 0 on the energy level H = (p_r² + p_z²) / 2m + V(r) with
    V(r) = (p_phi − r A_phi)² / (2 m r²): r spread over the allowed interval V(r) < H, and the
    momentum left, P = √(2m (H − V(r))), split as p_z = s · P along the axis and p_r across it, with s
    from 0.05 to 0.6 (members with a small s stay outside the loss cone, trapped between the mirrors
    as long as their magnetic moment is kept; the others escape along the axis)."""
    parameters = dict(spec.system.parameters)
    m, b0 = parameters["m"], parameters["B0"]
    p_phi = spec.p0[2]
    potential = lambda r: (p_phi - 0.5 * b0 * r**2) ** 2 / (2 * m * r**2)  # noqa: E731
    r = np.linspace(0.2, 5.0, 200_001)
    allowed = r[potential(r) < energy]
    r0 = np.linspace(allowed[0], allowed[-1], count + 2)[1:-1]
    momentum = np.sqrt(2 * m * (energy - potential(r0)))
    pitch = np.linspace(0.05, 0.6, count)
    return {"initial.q.r": r0, "initial.p.r": momentum * np.sqrt(1 - pitch**2), "initial.p.z": momentum * pitch}


def section(result):
    """The upward crossings of z = 0 of every member, (r, p_r) by linear interpolation between rows."""
    r, z = result.q[:, :, 0], result.q[:, :, 1]
    pr = result.p[:, :, 0]
    up = (z[:, :-1] < 0) & (z[:, 1:] >= 0)
    member, row = np.nonzero(up)
    s = -z[member, row] / (z[member, row + 1] - z[member, row])
    at = lambda a: a[member, row] + s * (a[member, row + 1] - a[member, row])  # noqa: E731
    return at(r), at(pr), member


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", type=int, default=300)
    parser.add_argument("--energy", type=float, default=0.1)
    parser.add_argument("--out", default="out", help="the directory of the figure (default: out, made if missing)")
    parser.add_argument("--dask", action="store_true", help="run the members on a local Dask cluster")
    args = parser.parse_args()

    spec = ddirac.load(SPEC, overrides={"time.step": 0.05, "time.steps": 100_000, "output.every": 10})
    members = members_on_energy_level(spec, args.energy, args.members)
    started = time.perf_counter()
    if args.dask:
        from dask.distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1") as cluster, Client(cluster) as client:
            result = ddirac.ensemble(spec, members=members, client=client, trajectories=True)
    else:
        result = ddirac.ensemble(spec, members=members, trajectories=True, progress=True)
    seconds = time.perf_counter() - started
    failed = int(np.sum(result.status == "failed"))
    print(f"{len(result)} members of {spec.steps} steps in {seconds:.1f} s ({failed} failed); "
          f"largest relative energy error {np.nanmax(result.diagnostics['energy_relative_error']):.2e}, "
          f"momentum map drift {np.nanmax(result.diagnostics['momentum_map_drift']):.1e}")
    r, pr, member = section(result)
    print(f"{len(r)} crossings of the midplane")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        path = Path(args.out) / "poincare_section.csv"
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savetxt(path, np.column_stack([member, r, pr]), delimiter=",", header="member,r,p_r", comments="")
        print(f"matplotlib is not installed: the crossings are in {path}")
        return
    fig, ax = plt.subplots(figsize=(7, 5), dpi=150)
    ax.scatter(r, pr, s=0.3, c=member, cmap="viridis", linewidths=0)
    ax.set_xlabel("r")
    ax.set_ylabel("p_r")
    ax.set_title(f"magnetic mirror, p_phi = {spec.p0[2]}, H = {args.energy}: crossings of z = 0 upwards")
    fig.tight_layout()
    figure = Path(args.out) / "poincare_section.png"
    figure.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(figure)
    print(f"wrote {figure}")


if __name__ == "__main__":
    main()
