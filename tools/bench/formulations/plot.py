#!/usr/bin/python3
"""The study's plot (RESULTS.md): per-step time of the four runs of ffr-bench-formulations.

Left: chains, time against the number of links (rigid and flexible links). Right: the
slider-crank's rod meshed ever finer, time against the rod's FE DOF (6 and 30 modes). Each
curve: absolute or relative formulation, inertia from the shape integrals (inv) or from the FE
mass matrix every evaluation (fe).

Usage: plot.py CHAINS.csv MESH.csv OUT.png   (the CSV files of ffr-bench-formulations --csv)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(f)]


def positive(v):
    x = float(v)
    return x if x > 0 else None


def series(data, key, x_key):
    pts = [(float(r[x_key]), positive(r[key])) for r in data]
    pts = [(x, y) for x, y in pts if y is not None]
    return [p[0] for p in pts], [p[1] for p in pts]


STYLE = {
    "abs_inv_us": ("absolute, invariants", "C0", "-"),
    "abs_fe_us": ("absolute, FE mass every step", "C0", "--"),
    "rel_inv_us": ("relative, invariants", "C3", "-"),
    "rel_fe_us": ("relative, FE mass every step", "C3", "--"),
}


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    chains, mesh, out = rows(sys.argv[1]), rows(sys.argv[2]), sys.argv[3]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.4))
    for group, marker in (("chain_rigid", "o"), ("chain_flexible", "s")):
        data = [r for r in chains if r["group"] == group]
        for key, (label, color, ls) in STYLE.items():
            x, y = series(data, key, "bodies")
            if x:
                ax1.plot(x, y, ls, color=color, marker=marker, ms=4,
                         label=f"{'rigid' if group == 'chain_rigid' else 'flexible'} links: {label}")
    ax1.set(xscale="log", yscale="log", xlabel="links in the chain", ylabel="us per step",
            title="Pendulum chains (h = 1 ms)")
    ax1.legend(fontsize=6.5)
    ax1.grid(True, which="both", alpha=0.3)
    for modes, marker in (("6", "o"), ("30", "^")):
        data = [r for r in mesh if r["modes"] == modes]
        for key, (label, color, ls) in STYLE.items():
            x, y = series(data, key, "fe_dof")
            if x:
                ax2.plot(x, y, ls, color=color, marker=marker, ms=4, label=f"{modes} modes: {label}")
    ax2.set(xscale="log", yscale="log", xlabel="FE DOF of the flexible rod", ylabel="us per step",
            title="Slider-crank, rod meshed ever finer (150 rad/s, h = 1 ms)")
    ax2.legend(fontsize=6.5)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
