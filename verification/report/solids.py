"""Solids (3D) in the verification report: Lamé's thick sphere from its gmsh part (errors and
rates of linear and quadratic RK, error against run time beside deal.II's figures quoted from
the issue that asked for them), the Neo-Hookean bar twisted far (no exact solution: the probe's
change), and a picture of each solid's von Mises field.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import matplotlib.pyplot as plt

from common import Context, Section, num, number, rate, rate_text, read_csv, table

SPHERE = Path("verification/lame-sphere/lame_sphere.toml")
BAR = Path("verification/twisted-bar/twisted_bar.toml")
PLOT_SOLID = Path("verification/plot_solid.py")

# deal.II Q1/Q2 on the same sphere, one thread (CG with ML algebraic multigrid and the rigid-body
# modes), as the issue quotes them: measured on this machine in an earlier session, on a loaded
# machine, not side by side with the runs below.
DEALII_QUOTED = [("deal.II Q2 (quoted)", 15e3, 1e-2, 0.85), ("deal.II Q2 (quoted)", 314e3, 1.26e-3, 25.0)]


def sections(ctx: Context) -> list[Section]:
    out = []
    for label, study in [("Lamé sphere", lame_sphere), ("twisted bar", twisted_bar)]:
        with ctx.step(f"solids: {label}"):
            out.append(study(ctx))
    return out


def picture(ctx: Context, run_folder: Path, name: str, scale: float, title: str, azimuth: float = 35.0) -> Path:
    figure = ctx.figure(name)
    subprocess.run([sys.executable, str(ctx.root / PLOT_SOLID), str(run_folder / "surface.vtu"), str(figure),
                    "von_mises", str(scale), title, str(azimuth)], check=True, capture_output=True)
    return figure


def lame_sphere(ctx: Context) -> Section:
    # Quick mode: linear RK on two levels and the solid meshed at 0.2 (its error rule is cheap).
    levels = {"linear": [0.4, 0.2]} if ctx.quick else {"linear": [0.4, 0.2, 0.133], "quadratic": [0.4, 0.3, 0.2]}
    coarse = ['domain.solid="thick_sphere_octant_02.geo"'] if ctx.quick else []
    rows, series, headlines = [], {}, []
    for order, spacings in levels.items():
        run = ctx.mfree_run("converge", SPHERE, f"lame_sphere_{order}",
                            coarse + [f'study.orders=["{order}"]', f"study.spacings={spacings}"])
        data = [r for r in read_csv(run.folder / "convergence.csv") if r["status"] == "ok"] if run.ok else []
        series[order] = data
        previous = None
        for r in data:
            h, l2, energy = number(r["spacing"]), number(r["l2_displacement"]), number(r["energy"])
            rl2 = rate(previous[1], l2, previous[0], h) if previous else float("nan")
            ren = rate(previous[2], energy, previous[0], h) if previous else float("nan")
            rows.append([order, f"{h:g}", r["dofs"], l2, rate_text(rl2), energy, rate_text(ren),
                         f"{number(r['seconds']):.3g}"])
            previous = (h, l2, energy, rl2, ren)
        if previous:
            expected = (2, 1) if order == "linear" else (3, 2)
            headlines.append((f"Lamé sphere, {order} RK: L2 and energy rates",
                              f"{expected[0]} and {expected[1]}",
                              f"{rate_text(previous[3])} and {rate_text(previous[4])}",
                              "quick: pre-asymptotic" if ctx.quick else
                              "yes" if previous[3] >= expected[0] - 0.3 and previous[4] >= expected[1] - 0.3 else
                              "no"))
    figure = ctx.figure("lame_sphere_work_precision")
    fig, ax = plt.subplots(figsize=(7, 5))
    for order, data in series.items():
        ax.loglog([number(r["seconds"]) for r in data], [number(r["energy"]) for r in data], "o-",
                  label=f"mfree {order} RK (this run, 2 threads)")
    ax.loglog([q[3] for q in DEALII_QUOTED], [q[2] for q in DEALII_QUOTED], "k^--",
              label="deal.II Q2, one thread (quoted, not side by side)")
    ax.set_xlabel("wall time of discretisation and solve [s]")
    ax.set_ylabel("relative energy-norm error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=100)
    plt.close(fig)
    h = 0.4 if ctx.quick else 0.2
    run = ctx.mfree_run("run", SPHERE, "lame_sphere_fields", coarse + [f"nodes.spacing={h}"])
    field = picture(ctx, run.folder, "lame_sphere_von_mises", 0.0, f"Lamé sphere: von Mises, linear RK, h = {h}",
                    azimuth=225.0)
    md = f"""**Problem** ([verification/lame-sphere/README.md](../verification/lame-sphere/README.md)). A hollow
sphere a = 1, b = 2 under internal pressure, E = 1000, ν = 0.3, one eighth from gmsh (tetrahedra of size
0.1, curved faces as flat triangles), slip walls on the three planes; u and grad u of Lamé's solution as
formulas in the scene; errors over the meshed solid by an independent rule. Lattice nodes, projected
quadrature (8 points a node) with VCI; the quadratic runs take support factor 3.

**Expected**: L2 and energy rates 2 and 1 (linear RK), 3 and 2 (quadratic RK).

**Observed** (`mfree converge`, 2 threads; time: discretisation and solve, not the error rule):

{table(["RK", "h", "DOFs", "L2 disp", "rate", "energy", "rate", "time [s]"], rows)}
{"(quick mode: linear RK, two levels, the solid meshed at 0.2)" if ctx.quick else ""}
Quadratic RK falls short of 3 and 2 on this curved solid while it reaches them on the cube (the test
"3D manufactured solution, quadratic RK"); with 27 quadrature points a node its rates rise (2.44 and
1.82 at h = 0.3 → 0.2): the projected gradients next to the curved surface are the lead. The deal.II
points are the issue's figures for Q2 on the same sphere (one thread, an earlier session, a loaded
machine): quoted, not measured side by side.

{ctx.image(figure, "Lamé sphere: energy error against run time, mfree linear and quadratic RK; deal.II Q2 quoted")}
{ctx.image(field, "Lamé sphere: von Mises stress on the octant's surface (undeformed; the planes of symmetry in front)")}
"""
    return Section("Solids: Lamé's thick sphere", md, headlines)


def twisted_bar(ctx: Context) -> Section:
    spacings = [0.1, 0.05] if ctx.quick else [0.1, 0.05, 0.025]
    run = ctx.mfree_run("converge", BAR, "twisted_bar", [f"study.spacings={spacings}"])
    data = [r for r in read_csv(run.folder / "convergence.csv") if r["status"] == "ok"] if run.ok else []
    probe_lines = [line for line in run.stdout.splitlines() if line.startswith("linear ")]
    rows = []
    for line in probe_lines:
        parts = line.split()
        rows.append(parts[1:])
    observed_rate = rows[-1][-2] if rows and len(rows[-1]) >= 2 else "—"
    h = 0.1 if ctx.quick else 0.05
    fields = ctx.mfree_run("run", BAR, "twisted_bar_fields", [f"nodes.spacing={h}"])
    field = picture(ctx, fields.folder, "twisted_bar_von_mises", 1.0, f"Twisted bar (60°): von Mises, deformed, h = {h}")
    md = f"""**Problem** ([verification/twisted-bar/README.md](../verification/twisted-bar/README.md)). A Neo-Hookean
bar [0, 1] × [0, 0.2]², clamped on x = 0, its end turned by 60° about its axis (prescribed displacement in
6 Newton load steps). No exact solution: u^h at the probe (0.5, 0.2, 0.2), its change between levels and
the observed rate of that change.

**Expected**: the change shrinks at about rate 2 (linear RK).

**Observed** (`mfree converge`, {len(data)} levels):

{table(["h", "DOFs", "u_x", "u_y", "u_z", "change", "rate", "time [s]"], rows)}
{ctx.image(field, "Twisted bar: von Mises stress on the deformed surface")}
"""
    headline = ("Twisted bar: probe change between levels", "rate about 2",
                observed_rate if not ctx.quick else f"change {rows[-1][-3] if rows else '—'} (quick: two levels)",
                "quick: two levels" if ctx.quick else "yes" if (observed_rate not in ("—", "-") and float(observed_rate) >= 1.7) else "no")
    return Section("Solids: a Neo-Hookean bar twisted far", md, [headline])
