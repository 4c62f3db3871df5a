#!/usr/bin/python3
"""Plots of an elasticity refinement study (mfree converge): errors against node spacing and
against run time, one line per cloud, RK order and quadrature scheme.

usage: plot_convergence.py convergence.csv OUTPUT_FOLDER
Writes error_vs_spacing.png and error_vs_time.png (temporary file, then rename).
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NORMS = [("l2_displacement", "relative L2 displacement error"),
         ("energy", "relative energy-norm error"),
         ("l2_stress", "relative L2 stress error")]
STYLE = {"projected + symmetric": "-", "projected + vci": (0, (5, 1)), "gauss_cells + vci": "-.", "gauss_cells": "--", "nodal": ":"}
MARK = {"lattice": "o", "perturbed": "s", "random": "^"}
COLOR = {"linear": "C0", "quadratic": "C3"}


def main():
    path, folder = sys.argv[1], sys.argv[2]
    series = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            if r["status"] == "ok":  # a failed run's row has empty cells and its reason
                method = r["scheme"] if r["consistency"] == "none" else f'{r["scheme"]} + {r["consistency"]}'
                series[(method, r["order"], r["cloud"])].append(r)
    # A norm no row has (a solid's study measures no stress error) gets no panel.
    norms = [(k, l) for k, l in NORMS if any(r[k] for rows in series.values() for r in rows)]
    for x_key, x_label, name, invert in [("spacing", "node spacing h", "error_vs_spacing.png", True),
                                         ("seconds", "wall time of the solve [s]", "error_vs_time.png", False)]:
        fig, axes = plt.subplots(1, len(norms), figsize=(6 * len(norms), 5.5), squeeze=False)
        axes = axes[0]
        for ax, (key, label) in zip(axes, norms):
            for (scheme, order, cloud), rows in sorted(series.items()):
                xs = [float(r[x_key]) for r in rows]
                ys = [float(r[key]) for r in rows]
                ax.loglog(xs, ys, linestyle=STYLE.get(scheme, "-"), marker=MARK.get(cloud, "x"),
                          color=COLOR.get(order, "k"), label=f"{scheme}, {order}, {cloud}")
            if invert:
                ax.invert_xaxis()
            ax.set_xlabel(x_label)
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=7)
        fig.tight_layout()
        out = os.path.join(folder, name)
        tmp = out + ".tmp.png"
        fig.savefig(tmp, dpi=100)
        os.replace(tmp, out)
        plt.close(fig)
    # The folder may be a staging one, renamed when the run succeeds: name the files only.
    print("plots: error_vs_spacing.png, error_vs_time.png")


if __name__ == "__main__":
    main()
