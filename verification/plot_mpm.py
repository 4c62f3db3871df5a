"""Plots of an MPM refinement study (mfree converge on an [mpm] scene).

Usage: /usr/bin/python3 plot_mpm.py mpm_convergence.csv OUTPUT_FOLDER

Writes, for every error time t/T in the CSV, mpm_error_vs_h_tXXX.png (RMS errors of
displacement, particle velocity, grid velocity at the particles and stress against cell size,
one line per method, update and particles per cell) and mpm_error_vs_time_tXXX.png (the same
errors against wall time of the run). With mpm_energy.csv beside the CSV, mpm_energy.png: the
energy balance (kinetic + strain - work of the body forces) through time of each run, relative
to its largest kinetic + strain energy.
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

FIELDS = (("displacement", "RMS displacement error [m]"),
          ("velocity", "RMS particle velocity error [m/s]"),
          ("grid_velocity", "RMS grid velocity error at particles [m/s]"),
          ("stress", "RMS Cauchy stress error [Pa]"))
MARKERS = {"classic": "o", "ugimp": "s", "cpgimp": "P", "cpdi": "^", "qcpdi": "X", "cpdi2": "<", "bspline": "D",
           "bspline_cubic": "v", "bspline_mls": "*"}


def label(key):
    method, update, mapping, ppc = key
    return f"{method} {update} {ppc} ppc" + ("" if mapping == "lumped" else f" {mapping}")


def error_plots(rows, out):
    by_time = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r["status"] != "ok":
            continue
        by_time[float(r["time_fraction"])][(r["method"], r["update"], r["mapping"], r["particles_per_cell"])].append(r)
    for frac, series in sorted(by_time.items()):
        tag = f"t{int(round(frac * 100)):03d}"
        for xkey, xlabel, name in (("spacing", "cell size h [m]", f"mpm_error_vs_h_{tag}.png"),
                                   ("seconds", "wall time of the run [s]", f"mpm_error_vs_time_{tag}.png")):
            fig, axes = plt.subplots(1, 4, figsize=(20, 4.8))
            for ax, (field, ylabel) in zip(axes, FIELDS):
                for key, rs in sorted(series.items()):
                    rs = sorted(rs, key=lambda r: -float(r["spacing"]))
                    # 9 particles per cell solid, other counts dashed
                    style = MARKERS.get(key[0], "o") + ("-" if key[3] == "9" else "--")
                    ax.loglog([float(r[xkey]) for r in rs], [float(r[field]) for r in rs], style,
                              label=label(key), markersize=4)
                if xkey == "spacing":
                    hs = sorted({float(r["spacing"]) for rs in series.values() for r in rs})
                    ys = [float(r[field]) for rs in series.values() for r in rs if float(r["spacing"]) == hs[-1]]
                    if ys:
                        y0 = min(ys)
                        ax.loglog(hs, [y0 * (h / hs[-1]) ** 2 for h in hs], "k:", label="slope 2")
                ax.xaxis.set_minor_formatter(NullFormatter())
                ax.set_xlabel(xlabel)
                ax.set_ylabel(ylabel)
                ax.grid(True, which="both", alpha=0.3)
            axes[0].legend(fontsize=6)
            fig.suptitle(f"MPM, axis-aligned vibration: errors at t = {frac:.2f} T")
            fig.tight_layout()
            fig.savefig(os.path.join(out, name), dpi=110)
            plt.close(fig)
            print(f"wrote {name}")  # in the run folder (a staging one until the run succeeds)


def energy_plot(path, out):
    runs = defaultdict(list)
    for r in csv.DictReader(open(path)):
        runs[(r["method"], r["update"], r["mapping"], r["particles_per_cell"], r["cells"])].append(r)
    if not runs:
        return
    fig, ax = plt.subplots(figsize=(9, 5))
    for key, rs in sorted(runs.items()):
        t = [float(r["time"]) for r in rs]
        total = [float(r["total"]) for r in rs]
        scale = max(float(r["kinetic"]) + float(r["strain"]) for r in rs)
        ax.plot(t, [(e - total[0]) / scale for e in total], label=f"{label(key[:4])}, {key[4]} cells")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("(E(t) - E(0)) / max(kinetic + strain)")
    ax.set_title("MPM energy balance: kinetic + strain - work of the body forces")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    name = os.path.join(out, "mpm_energy.png")
    fig.savefig(name, dpi=110)
    print(f"wrote {name}")


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    out = sys.argv[2]
    error_plots(rows, out)
    energy = os.path.join(os.path.dirname(sys.argv[1]), "mpm_energy.csv")
    if os.path.exists(energy):
        energy_plot(energy, out)


if __name__ == "__main__":
    main()
