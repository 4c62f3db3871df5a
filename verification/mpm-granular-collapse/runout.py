"""Final runout and height of the granular column collapses (verification/mpm-granular-collapse)
against the quasi-2D experimental scaling laws.

Usage: /usr/bin/python3 runout.py RESULTS [--plot FILE] [--check]
  RESULTS  a folder with one run per aspect ratio, each a subfolder with particles.csv (the end
           state), series.pvd with its particles_NNNN.vtu frames and energy.csv, as
           `mfree run column.toml` writes them (run.sh: RESULTS/a0.5, a1, a2)
  --plot   the figure (default RESULTS/runout.png): the final deposits scaled by L0, and the
           runout against a with the experimental laws and their spread
  --check  the fast test (check_quick.sh): exit 1 unless every run in RESULTS has
           1.0 <= (L_inf - L0) / L0 <= 2.5, a final front speed below 0.05 m/s, no particle
           lost, a mass defect (summary.json) below 1e-10 and a deposit area within 10 % of L0 H0

Measured, per run:
  L0, H0     from the reference positions X, Y of particles.csv (particles sit at the centres of
             the sub-cells of spacing s: L0 = max X + min X, s = 2 min X)
  front      the largest x among the particles with at least N_NEIGHBOURS = 4 others within
             r = 2 s (= h at 4 particles per cell); a few grains thrown ahead of the deposit do
             not count. L_inf = front, runout = (L_inf - L0) / L0.
  H_inf      the highest such particle plus s / 2 (the deposit's top: at the left wall), / L0
  front speed at the end: (front(t_end) - front(t_end - 0.1 s)) / 0.1 s from the .vtu frames
             (python3-vtk9, which libvtk9-dev of .ci/setup brings); and the largest particle
             speed at t_end
  area       the deposit's area from its surface (the highest particle per column of width s,
             plus s / 2), / (L0 H0): the flow is nearly isochoric (psi = 0, elastic strains
             ~1e-3), so a large change would mean particles lost or packed

Experimental laws (quasi-2D columns released in a channel; a = H0 / L0, runout R = (L_inf - L0) / L0):
  Lube, Huppert, Sparks & Freundt 2005, "Collapses of two-dimensional granular columns",
    Phys. Rev. E 72, 041301 (sand, rice, sugar, couscous; the 2-D companion of their
    axisymmetric study, J. Fluid Mech. 508 (2004) 175-199):
      R = 1.2 a            for a < 1.8
      R = 1.9 a^(2/3)      for a > 2.8   (1.8 < a < 2.8: the transition, both shown)
      H_inf / L0 = a       for a < 1.15  (the top of the column is not reached)
      H_inf / L0 = a^(2/5) for a > 1.15
  Lajeunesse, Monnier & Homsy 2005, "Granular slumping on a horizontal surface",
    Phys. Fluids 17, 103302 (glass beads in a channel):
      R = 1.8 a            for a < 3
      R = 2.3 a^(2/3)      for a > 3
    (the prefactors as tabulated from their data by Lagrée, Staron & Popinet 2011,
    J. Fluid Mech. 686, 378-408, eq. 3.1; not checked against the original paper here)
  Spread: the two groups' prefactors differ by 1.5x (1.2 vs 1.8) for the same law, the
  difference of materials (angular sand vs smooth beads) and of the release; Balmforth &
  Kerswell 2005 (J. Fluid Mech. 538, 399-428) find the exponent 0.9 +- 0.1 in wide channels
  and prefactors that depend on the material. The band between the Lube and Lajeunesse laws is
  the experimental spread used here: no single number is "the" experiment.
"""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

N_NEIGHBOURS = 4
LUBE = dict(linear=1.2, a_linear=1.8, power=1.9, a_power=2.8)
LAJEUNESSE = dict(linear=1.8, a_linear=3.0, power=2.3, a_power=3.0)


def law(c, a):
    """The runout law c at a; in a transition gap (a_linear < a < a_power) both branches."""
    lin, pw = c["linear"] * a, c["power"] * a ** (2.0 / 3.0)
    if a <= c["a_linear"]:
        return lin, lin
    if a >= c["a_power"]:
        return pw, pw
    return min(lin, pw), max(lin, pw)


def lube_height(a):
    return a if a < 1.15 else a ** 0.4


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0] if k != "body"}


def neighbours_enough(p, pts, r):
    d2 = np.sum((pts - p) ** 2, axis=1)
    return np.count_nonzero(d2 < r * r) - 1 >= N_NEIGHBOURS


def front(pts, r):
    """The largest x of a particle with N_NEIGHBOURS others within r."""
    for k in np.argsort(-pts[:, 0]):
        if neighbours_enough(pts[k], pts, r):
            return pts[k, 0]
    return float("nan")


def top(pts, r):
    for k in np.argsort(-pts[:, 1]):
        if neighbours_enough(pts[k], pts, r):
            return pts[k, 1]
    return float("nan")


def surface(pts, s, xmax):
    """Highest particle per column of width s (+ s/2): the deposit's surface y(x)."""
    edges = np.arange(0.0, xmax + s, s)
    k = np.digitize(pts[:, 0], edges) - 1
    y = np.zeros(len(edges) - 1)
    np.maximum.at(y, k, pts[:, 1] + 0.5 * s)
    return edges, y


def frames(folder):
    """(time, file) of series.pvd."""
    tree = ET.parse(os.path.join(folder, "series.pvd"))
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in tree.iter("DataSet")]


def read_vtu(path):
    import vtk  # python3-vtk9
    from vtk.util.numpy_support import vtk_to_numpy

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    out = reader.GetOutput()
    pts = vtk_to_numpy(out.GetPoints().GetData())[:, :2]
    v = out.GetPointData().GetArray("velocity")
    return pts, (vtk_to_numpy(v)[:, :2] if v is not None else None)


def measure(folder):
    p = read_csv(os.path.join(folder, "particles.csv"))
    s = 2.0 * p["X"].min()
    L0, H0 = p["X"].max() + p["X"].min(), p["Y"].max() + p["Y"].min()
    r = 2.0 * s
    pts = np.c_[p["x"], p["y"]]
    m = dict(folder=folder, a=H0 / L0, L0=L0, H0=H0, s=s, n=len(pts), pts=pts)
    m["front"] = front(pts, r)
    m["farthest"] = pts[:, 0].max()
    m["runout"] = (m["front"] - L0) / L0
    m["height"] = (top(pts, r) + 0.5 * s) / L0
    edges, y = surface(pts, s, pts[:, 0].max())
    m["area"] = float(np.sum(y) * s) / (L0 * H0)
    thick = np.nonzero(y >= 4.0 * s)[0]  # where the deposit is at least 2 h (4 s) thick
    m["front_thick"] = edges[thick[-1] + 1] if len(thick) else float("nan")
    m["speed_end_max"] = float(np.hypot(p["vx"], p["vy"]).max())
    # the front through time, from the frames
    hist = []
    n0 = None
    if os.path.exists(os.path.join(folder, "series.pvd")):
        for t, f in frames(folder):
            fp, _ = read_vtu(f)
            n0 = n0 or len(fp)
            hist.append((t, front(fp, r)))
    m["history"] = np.array(hist) if hist else np.zeros((0, 2))
    m["n0"] = n0 if n0 else m["n"]
    m["front_speed"] = float("nan")
    if len(hist) >= 2:
        t_end = hist[-1][0]
        k = min(range(len(hist)), key=lambda i: abs(hist[i][0] - (t_end - 0.1)))
        if hist[k][0] < t_end:
            m["front_speed"] = (hist[-1][1] - hist[k][1]) / (t_end - hist[k][0])
        m["t_end"] = t_end
        # when the front last moved by more than s: its arrest time
        moved = [t for (t, x) in hist if hist[-1][1] - x > s]
        m["t_stop"] = max(moved) if moved else 0.0
    summary = os.path.join(folder, "summary.json")
    m["seconds"], m["threads"], m["mass_defect"] = float("nan"), 0, float("nan")
    if os.path.exists(summary):
        with open(summary) as f:
            js = json.load(f)
        m["seconds"] = js.get("total_seconds", float("nan"))
        m["threads"] = js.get("threads", 0)
        m["mass_defect"] = js.get("mass_defect", float("nan"))
    return m


def fmt_law(lo, hi):
    return f"{lo:.2f}" if abs(hi - lo) < 1e-12 else f"{lo:.2f}-{hi:.2f}"


def table(runs):
    print("| a | particles | runout (L_inf - L0)/L0 | Lube 2005 | Lajeunesse 2005 | ratio to Lube | ratio to Lajeunesse "
          "| front where >= 2 h thick, (L - L0)/L0 | H_inf/L0 | Lube H_inf/L0 | front speed at end [m/s] | front stops by [s] | area / L0 H0 | run [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for m in runs:
        a = m["a"]
        lu, la = law(LUBE, a), law(LAJEUNESSE, a)
        ratio_lu = m["runout"] / lu[0] if lu[0] == lu[1] else f"{m['runout'] / lu[1]:.2f}-{m['runout'] / lu[0]:.2f}"
        ratio_lu = f"{ratio_lu:.2f}" if isinstance(ratio_lu, float) else ratio_lu
        print(f"| {a:g} | {m['n']} | {m['runout']:.2f} | {fmt_law(*lu)} | {fmt_law(*la)} | {ratio_lu} | "
              f"{m['runout'] / la[0]:.2f} | {(m['front_thick'] - m['L0']) / m['L0']:.2f} | {m['height']:.2f} | {lube_height(a):.2f} | {m['front_speed']:.3f} | "
              f"{m.get('t_stop', float('nan')):.2f} | {m['area']:.3f} | {m['seconds']:.0f} |")


def plot(runs, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [1.6, 1]})
    colours = {id(m): f"C{k}" for k, m in enumerate(runs)}
    for m in reversed(runs):  # the tallest behind
        L0 = m["L0"]
        (line,) = ax1.plot(m["pts"][:, 0] / L0, m["pts"][:, 1] / L0, ".", ms=0.6, alpha=0.5,
                           color=colours[id(m)])
        ax1.plot([0, 1, 1], [m["H0"] / L0, m["H0"] / L0, 0], "--", lw=0.8, color=line.get_color())
        ax1.axvline(m["front"] / L0, lw=0.8, color=line.get_color(),
                    label=f"a = {m['a']:g}: L_inf/L0 = {m['front'] / L0:.2f}")
        for a_, lu_ in [(m["a"], law(LUBE, m["a"]))]:
            ax1.plot([1 + lu_[0]], [0], "v", color=line.get_color(), ms=7)
    ax1.set_xlabel("x / L0")
    ax1.set_ylabel("y / L0")
    ax1.set_aspect("equal")
    ax1.set_ylim(0, max(m["H0"] / m["L0"] for m in runs) * 1.05)
    ax1.set_title("Final deposits (dashed: initial column; line: measured front; triangle: Lube 2005)")
    handles, labels = ax1.get_legend_handles_labels()
    ax1.legend(handles[::-1], labels[::-1], fontsize=8)

    a = np.linspace(0.2, 3.2, 301)
    gap = (a > 1.8) & (a < 2.8)
    lube_lin, lube_pow = 1.2 * a, 1.9 * a ** (2 / 3)
    laj = np.where(a <= 3.0, 1.8 * a, 2.3 * a ** (2 / 3))
    lube_lo = np.where(a <= 1.8, lube_lin, np.where(gap, np.minimum(lube_lin, lube_pow), lube_pow))
    lube_hi = np.where(a <= 1.8, lube_lin, np.where(gap, np.maximum(lube_lin, lube_pow), lube_pow))
    ax2.fill_between(a, np.minimum(lube_lo, laj), np.maximum(lube_hi, laj), color="0.87",
                     label="spread: between the two experiments' laws")
    ax2.plot(a, np.where(a <= 1.8, lube_lin, np.nan), "k-",
             label="Lube et al. 2005: 1.2 a (a < 1.8), 1.9 a^(2/3) (a > 2.8)")
    ax2.plot(a, np.where(a >= 2.8, lube_pow, np.nan), "k-")
    ax2.plot(a, np.where(gap, lube_lin, np.nan), "k:", lw=0.8, label="Lube: either branch (transition)")
    ax2.plot(a, np.where(gap, lube_pow, np.nan), "k:", lw=0.8)
    ax2.plot(a, laj, "k--", label="Lajeunesse et al. 2005: 1.8 a (a < 3), 2.3 a^(2/3)")
    ax2.plot([m["a"] for m in runs], [m["runout"] for m in runs], "ro", label="mfree MPM, DP phi = 30 deg")
    ax2.set_xlabel("a = H0 / L0")
    ax2.set_ylabel("(L_inf - L0) / L0")
    ax2.set_xlim(0, 3.2)
    ax2.set_ylim(0, 6)
    ax2.legend(fontsize=7, loc="upper left")
    ax2.set_title("Runout against aspect ratio")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print(f"wrote {path}")


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    results = argv[1]
    check = "--check" in argv
    out = argv[argv.index("--plot") + 1] if "--plot" in argv else os.path.join(results, "runout.png")
    folders = sorted((os.path.join(results, d) for d in os.listdir(results)
                      if os.path.exists(os.path.join(results, d, "particles.csv"))))
    if not folders:
        print(f"runout.py: no run (a folder with particles.csv) in {results}", file=sys.stderr)
        return 1
    runs = sorted((measure(f) for f in folders), key=lambda m: m["a"])
    table(runs)
    if check:
        ok = True
        for m in runs:
            tests = [
                (1.0 <= m["runout"] <= 2.5, f"runout {m['runout']:.3f} in [1.0, 2.5]"),
                (abs(m["front_speed"]) < 0.05, f"front speed at the end {m['front_speed']:.4f} m/s below 0.05"),
                (m["n"] == m["n0"], f"particles at the end {m['n']} = at the start {m['n0']}"),
                (m["mass_defect"] < 1e-10, f"mass defect (summary.json) {m['mass_defect']:.1e} below 1e-10"),
                (abs(m["area"] - 1.0) < 0.10, f"deposit area / L0 H0 = {m['area']:.3f} within 10 % of 1"),
            ]
            for good, what in tests:
                print(f"{'ok  ' if good else 'FAIL'} a = {m['a']:g}: {what}")
                ok = ok and good
        print("granular collapse check: " + ("passed" if ok else "FAILED"))
        return 0 if ok else 1
    plot(runs, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
