#!/usr/bin/python3
"""Plots of the integration-accuracy study: error against spacing and against run time.

usage: plot.py integration.csv OUTPUT_FOLDER
One panel per test function; one line per scheme, cloud and RK order.
Each PNG is written to a temporary file and renamed into place.
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"rk": "-", "voronoi": "--", "gauss_cells": ":", "equal": "-."}
MARK = {"lattice": "o", "random": "s", "perturbed": "^", "-": "x"}


def load(path):
    series = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            key = (r["function"], r["scheme"], r["cloud"], r["order"])
            series[key].append(r)
    return series


def label(scheme, cloud, order):
    name = {"rk": "RK weights", "voronoi": "Voronoi", "gauss_cells": "Gauss cells", "equal": "equal"}[scheme]
    parts = [name] + ([order] if order != "-" else []) + ([cloud] if cloud != "-" else [])
    return ", ".join(parts)


def plot(series, x_key, x_label, out, invert):
    functions = sorted({k[0] for k in series})
    fig, axes = plt.subplots(1, len(functions), figsize=(6.5 * len(functions), 5), squeeze=False)
    for ax, fn in zip(axes[0], functions):
        for (f, scheme, cloud, order), rows in sorted(series.items()):
            if f != fn:
                continue
            xs = [float(r[x_key]) for r in rows]
            ys = [max(float(r["relative_error"]), 1e-16) for r in rows]
            color = "C%d" % (["rk-linear", "rk-quadratic", "voronoi", "gauss_cells", "equal"].index(
                scheme + ("-" + order if scheme == "rk" else "")))
            ax.loglog(xs, ys, STYLE[scheme], marker=MARK.get(cloud, "x"), color=color,
                      label=label(scheme, cloud, order))
        if invert:
            ax.invert_xaxis()
        ax.set_xlabel(x_label)
        ax.set_ylabel("relative integration error")
        ax.set_title(f"{fn}: error against {x_label.split(' ')[0]}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)
    plt.close(fig)


def main():
    path, folder = sys.argv[1], sys.argv[2]
    series = load(path)
    plot(series, "spacing", "spacing h = sqrt(|Omega| / N)", os.path.join(folder, "error_vs_spacing.png"), True)
    plot(series, "seconds", "time to build the rule [s]", os.path.join(folder, "error_vs_time.png"), False)


if __name__ == "__main__":
    main()
