"""The Taylor-bar impact: energy balance per grid and the final shape.

Usage: /usr/bin/python3 plot.py RESULTS_FOLDER

RESULTS_FOLDER holds cells_N/ runs of bar.toml (energy.csv, particles.csv, series.pvd). Prints per
grid the largest drift of kinetic + stored + dissipated from the initial kinetic energy, the
split at the end, the final length L_f (the bar's largest x: it stands on the wall at x = 0) and
the mushroom's half-height at the wall; writes taylor_bar.png: the energies through time on the
finest grid and its final particles coloured by the equivalent plastic strain.
"""
import csv
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

L0, H0, KINETIC0 = 0.032, 0.008, 0.5 * 2700 * 0.032 * 0.008 * 200.0**2


def rows(path):
    return list(csv.DictReader(open(path)))


def last_frame(run):
    """The last particles_NNNN.vtu of the run's series."""
    files = re.findall(r'file="([^"]+)"', (run / "series.pvd").read_text())
    return run / files[-1]


def read_particles(vtu):
    import vtk  # python3-vtk9
    from vtk.util.numpy_support import vtk_to_numpy

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(vtu))
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())
    alpha = vtk_to_numpy(grid.GetPointData().GetArray("plastic_strain"))
    return points[:, 0], points[:, 1], alpha


def main():
    folder = pathlib.Path(sys.argv[1])
    runs = sorted(folder.glob("cells_*"), key=lambda p: int(p.name.split("_")[1]))
    print(f"initial kinetic energy {KINETIC0:.1f} J/m")
    print(f"{'cells':>6} {'drift':>8} {'kinetic':>9} {'stored':>9} {'dissipated':>11} {'L_f/L0':>7} {'h_wall/H0':>9}")
    for run in runs:
        e = rows(run / "energy.csv")
        drift = max(abs(float(r["total"]) - KINETIC0) for r in e) / KINETIC0
        end = e[-1]
        p = rows(run / "particles.csv")
        length = max(float(r["x"]) for r in p)
        wall = max(float(r["y"]) for r in p if float(r["x"]) < 0.05 * L0)
        print(f"{run.name.split('_')[1]:>6} {drift:8.2%} {float(end['kinetic']):9.1f} {float(end['strain']):9.1f} "
              f"{float(end['dissipated']):11.1f} {length / L0:7.3f} {wall / H0:9.3f}")
    finest = runs[-1]
    e = rows(finest / "energy.csv")
    t = [1e6 * float(r["time"]) for r in e]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [1, 1.4]})
    for key, label in [("kinetic", "kinetic"), ("strain", "stored (elastic)"), ("dissipated", "dissipated (plastic work)"),
                       ("total", "kinetic + stored + dissipated")]:
        left.plot(t, [float(r[key]) for r in e], label=label)
    left.axhline(KINETIC0, color="k", ls=":", lw=0.8)
    left.set_xlabel("t [µs]")
    left.set_ylabel("energy [J/m]")
    left.set_title(f"energy balance, {finest.name.replace('_', ' ')}")
    left.legend(fontsize=8)
    left.grid(True, alpha=0.3)
    x, y, alpha = read_particles(last_frame(finest))
    # The colour scale stops at the 99th percentile: a few particles in the wall's corner strain far more.
    s = right.scatter(1e3 * x, 1e3 * y, c=alpha, s=2, cmap="viridis", vmax=sorted(alpha)[int(0.99 * (len(alpha) - 1))])
    right.plot([2, 34, 34, 2, 2], [0, 0, 8, 8, 0], "k--", lw=0.8, label="the bar before impact")
    right.axvline(0.0, color="k", lw=2)
    right.set_aspect("equal")
    right.set_xlabel("x [mm]")
    right.set_ylabel("y [mm] (symmetry at y = 0)")
    right.set_title(f"final shape at t = {t[-1]:.0f} µs")
    right.legend(fontsize=8, loc="upper right")
    fig.colorbar(s, ax=right, label="equivalent plastic strain (to its 99th percentile)")
    fig.tight_layout()
    fig.savefig(folder / "taylor_bar.png", dpi=120)
    print(f"wrote {folder / 'taylor_bar.png'}")


if __name__ == "__main__":
    main()
