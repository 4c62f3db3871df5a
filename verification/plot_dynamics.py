"""Plots of a dynamics refinement study (mfree converge on a [dynamics] scene).

Usage: /usr/bin/python3 plot_dynamics.py convergence.csv OUTPUT_FOLDER

Writes dynamics_convergence.png (RMS errors of displacement, velocity and stress against node
spacing, one line per time scheme and error time) and dynamics_error_vs_time.png (the same
errors against wall time of the run).
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    out = sys.argv[2]
    series = defaultdict(list)
    for r in rows:
        series[(r["time_scheme"], float(r["time"]))].append(r)
    end = max(float(r["time"]) for r in rows)
    for xkey, xlabel, name in (("spacing", "node spacing h [m]", "dynamics_convergence.png"),
                               ("seconds", "wall time [s]", "dynamics_error_vs_time.png")):
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
        for ax, (field, label) in zip(axes, (("displacement", "RMS displacement error [m]"),
                                             ("velocity", "RMS velocity error [m/s]"),
                                             ("stress", "RMS Cauchy stress error [Pa]"))):
            for (scheme, t), rs in sorted(series.items()):
                rs = sorted(rs, key=lambda r: float(r["spacing"]))
                style = "-o" if scheme == "central_difference" else "--s"
                ax.loglog([float(r[xkey]) for r in rs], [float(r[field]) for r in rs], style,
                          label=f"{scheme}, t = {t / end:.2f} T")
            if xkey == "spacing":
                hs = sorted({float(r["spacing"]) for r in rows})
                ref = [float(r[field]) for r in rows if float(r["spacing"]) == hs[-1]]
                if ref:
                    y0 = min(ref)
                    ax.loglog(hs, [y0 * (h / hs[-1]) ** 2 for h in hs], "k:", label="slope 2")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=7)
        fig.suptitle("Axis-aligned vibration, total-Lagrangian meshfree")
        fig.tight_layout()
        fig.savefig(f"{out}/{name}", dpi=120)
        print(f"wrote {name}")  # in the run folder (a staging one until the run succeeds)


if __name__ == "__main__":
    main()
