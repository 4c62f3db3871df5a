"""Load-deflection curve of a total-Lagrangian static run (mfree run on a [newton] scene).

Usage: /usr/bin/python3 plot_load_deflection.py load_steps.csv OUTPUT_FOLDER

Writes load_deflection.png: the load factor against the magnitudes of the probe's displacement components, with the
small-strain (linear) prediction when the scene has an exact solution (cells left empty otherwise).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    out = sys.argv[2]
    lam = [0.0] + [float(r["load_factor"]) for r in rows]
    uy = [0.0] + [abs(float(r["probe_uy"])) for r in rows]
    ux = [0.0] + [abs(float(r["probe_ux"])) for r in rows]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.plot(uy, lam, "-o", ms=3, label="total-Lagrangian: $|u_y|$ at the probe")
    ax.plot(ux, lam, "-s", ms=3, label="total-Lagrangian: $|u_x|$ at the probe")
    if all(r["linear_probe_uy"] for r in rows):
        linear = [0.0] + [abs(float(r["linear_probe_uy"])) for r in rows]
        ax.plot(linear, lam, "k--", label="small strain (the scene's exact solution)")
        ax.set_xlim(0, 1.15 * max(uy + ux))
    ax.set_xlabel("probe displacement magnitude")
    ax.set_ylabel("load factor")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{out}/load_deflection.png", dpi=120)
    print("wrote load_deflection.png")  # in the run folder (a staging one until the run succeeds)


if __name__ == "__main__":
    main()
