"""Plasticity: the verification cases of the laws with history, in both solvers.

    material point      J2 along uniaxial strain through yield, unloading and reverse yield
                        against its closed form; tension then shear: first-order convergence
                        of the radial return in the increment
    plastic cylinder    total-Lagrangian statics to 98 % of the limit load: elastic-plastic
                        radius against the classical solution, Newton, the collapse beyond p_L
    strip footing       Drucker–Prager (associative) to 98 % of Prandtl's collapse load, and past it
    Taylor bar          MPM impact of a J2 bar on a wall: kinetic + stored + dissipated energy
    granular collapse   MPM Drucker–Prager column collapse: runout against the experiments

Each case lives in its folder under verification/ with its README (problem, expected result,
measured figures); the scripts there measure the runs, and this module imports them.
"""
from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
from pathlib import Path

from common import Context, Section, num, number, read_csv, table

MATERIAL_POINT = Path("verification/material-point")
CYLINDER = Path("verification/plastic-cylinder")
FOOTING = Path("verification/plastic-footing")
TAYLOR_BAR = Path("verification/mpm-taylor-bar")
GRANULAR = Path("verification/mpm-granular-collapse")


def sections(ctx: Context) -> list[Section]:
    out = []
    for label, study in [("material-point paths", material_point), ("plastic cylinder", plastic_cylinder),
                         ("strip footing", strip_footing),
                         ("Taylor bar", taylor_bar), ("granular collapse", granular_collapse)]:
        with ctx.step(f"plasticity: {label}"):
            out.append(study(ctx))
    return out


def script(ctx: Context, path: Path):
    """A verification folder's Python script, imported as a module."""
    spec = importlib.util.spec_from_file_location(path.stem + "_" + path.parent.name.replace("-", "_"), ctx.root / path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def yes(flag: bool) -> str:
    return "yes" if flag else "no"


# ---------------------------------------------------------------------------------------------
# Material-point paths

def uniaxial_closed_form() -> dict:
    """The closed form of verification/material-point/README.md for uniaxial.toml (small-strain J2,
    E = 200e3, nu = 0.3, sigma_y = 250, H_iso = 10e3, H_kin = 20e3; eps(t) = 0.01 (t <= 1 ? t : 2 - t)):
    first yield, alpha at the turning point, reverse yield and alpha at t = 3."""
    e_mod, nu, sy, h_iso, h_kin = 200e3, 0.3, 250.0, 10e3, 20e3
    mu = e_mod / (2 * (1 + nu))
    a = math.sqrt(2.0 / 3.0)
    c = 2 * mu + 2.0 / 3.0 * (h_iso + h_kin)
    e_max = 0.01
    gamma1 = a * (2 * mu * e_max - sy) / c
    alpha1 = a * gamma1
    k1 = sy + h_iso * alpha1
    e_reverse = -e_max + k1 / mu
    q_end = 2 * mu * a * (0.01 - e_reverse) / c  # q - q_1 at e = +0.01
    return {"t_yield": sy / (2 * mu) / e_max, "alpha_1": alpha1, "t_reverse": 2.0 + e_reverse / e_max,
            "alpha_end": alpha1 + a * q_end}


def material_point(ctx: Context) -> Section:
    exact = uniaxial_closed_form()
    run = ctx.mfree_run("run", MATERIAL_POINT / "uniaxial.toml", "material_point/uniaxial")
    rows = read_csv(run.folder / "path.csv")
    t = [number(r["time"]) for r in rows]
    alpha = [number(r["alpha"]) for r in rows]
    first = next(k for k in range(len(rows)) if alpha[k] > 0.0)
    at_one = min(range(len(rows)), key=lambda k: abs(t[k] - 1.0))
    reverse = next(k for k in range(at_one + 1, len(rows)) if alpha[k] > alpha[at_one])
    step = t[1] - t[0]
    uniaxial = [
        ["first yield t", f"{exact['t_yield']:.6f}", f"({t[first - 1]:.4f}, {t[first]:.4f}]",
         yes(t[first - 1] <= exact["t_yield"] <= t[first])],
        ["alpha at t = 1", f"{exact['alpha_1']:.9e}", f"{alpha[at_one]:.9e}",
         yes(abs(alpha[at_one] - exact["alpha_1"]) <= 1e-10 * exact["alpha_1"])],
        ["reverse yield t", f"{exact['t_reverse']:.6f}", f"({t[reverse - 1]:.4f}, {t[reverse]:.4f}]",
         yes(t[reverse - 1] <= exact["t_reverse"] <= t[reverse])],
        ["alpha at t = 3", f"{exact['alpha_end']:.9e}", f"{alpha[-1]:.9e}",
         yes(abs(alpha[-1] - exact["alpha_end"]) <= 1e-10 * exact["alpha_end"])],
    ]
    # Tension then shear: the radial return is backward Euler of the rate equations, first order
    # in the increment; the 10^6-increment run is the reference of the coarser ones.
    finals = {}
    for n in (1000, 10000, 1000000):
        r = ctx.mfree_run("run", MATERIAL_POINT / "tension_shear.toml", f"material_point/tension_shear_{n}",
                          [f"path.increments={n}", f"path.record_every={n // 1000}"])
        last = read_csv(r.folder / "path.csv")[-1]
        finals[n] = {k: number(last[k]) for k in ("sigma_xx", "sigma_yy", "sigma_xy", "alpha")}
    ref = finals[1000000]

    def error(n):
        s = math.sqrt(sum((finals[n][k] - ref[k]) ** 2 for k in ("sigma_xx", "sigma_yy", "sigma_xy")))
        return s / math.sqrt(sum(ref[k] ** 2 for k in ("sigma_xx", "sigma_yy", "sigma_xy")))

    e1, e2 = error(1000), error(10000)
    order = math.log10(e1 / e2)
    headlines = [
        ("Material point: uniaxial strain (J2)", "first and reverse yield, alpha to 1e-10 of the closed form",
         f"alpha(1) {alpha[at_one]:.6e}, alpha(3) {alpha[-1]:.6e}", yes(all(row[3] == "yes" for row in uniaxial))),
        ("Material point: tension then shear (J2)", "radial return first order in the increment (0.8-1.2)",
         f"stress error {num(e1)} -> {num(e2)} at 10^3 -> 10^4 increments: order {order:.2f}",
         yes(0.8 <= order <= 1.2)),
    ]
    md = f"""**Problem** ([{MATERIAL_POINT}/README.md](../{MATERIAL_POINT}/README.md)). One material point of
small-strain J2 (E = 200e3, ν = 0.3, σ_y = 250, linear isotropic and kinematic hardening) driven
along a deformation gradient F(t) by `mfree run` of a `[path]` scene: uniaxial strain compressed to
ε_yy = −0.01, unloaded and stretched to +0.01 (3000 increments); tension to ε_yy = 0.008, then shear
to 0.01 at constant stretch.

**Expected.** Along the uniaxial path the radial return is exact for any increment (the path is
radial in deviatoric space and the hardening linear): first yield, the plastic strain at the
turning point, reverse yield (before zero strain: the back stress moved the elastic range) and the
final plastic strain meet the closed form to round-off. The tension–shear path turns the flow
direction: the return is backward Euler of the rate equations, first order in the increment
(`tests/materials/test_strain_path.cpp` checks it against a Runge–Kutta integration to 1e-6).

**Observed** (uniaxial; yield times bracketed by the increments of {step:.0e}):

{table(["quantity", "closed form", "mfree", "agrees"], uniaxial)}
Tension then shear, at t = 2 against 10^6 increments: relative stress error {num(e1)} (10^3
increments), {num(e2)} (10^4), observed order {order:.2f}.
"""
    return Section("Plasticity: material-point paths", md, headlines)


# ---------------------------------------------------------------------------------------------
# Plastic thick cylinder

def plastic_cylinder(ctx: Context) -> Section:
    check = script(ctx, CYLINDER / "check.py")
    sets = ["nodes.spacing=0.1"] if ctx.quick else []
    run = ctx.mfree_run("run", CYLINDER / "cylinder.toml", "plastic_cylinder", sets + ["output.fields=[]"])
    rows = read_csv(run.folder / "load_steps.csv")
    lines, worst = [], 0.0
    for r in rows:
        p = 0.98 * number(r["load_factor"])
        area = number(r["plastic_area"])
        c = math.sqrt(1.0 + 4 * area / math.pi) if area > 0 else None
        exact = check.hill_radius(p * check.P_LIMIT)
        error = ""
        if c is not None and exact is not None:
            worst = max(worst, abs(c - exact) / exact)
            error = f"{100 * (c - exact) / exact:+.2f} %"
        lines.append([f"{p:.4f}", f"{number(r['probe_ux']):.4e}", f"{c:.4f}" if c else "elastic",
                      f"{exact:.4f}" if exact else "–", error, r["iterations"], r["cutbacks"]])
    iterations = [int(r["iterations"]) for r in rows]
    cutbacks = sum(int(r["cutbacks"]) for r in rows)
    figure = ctx.figure("plastic_cylinder")
    subprocess.run([sys.executable, str(ctx.root / CYLINDER / "check.py"), str(run.folder / "load_steps.csv"),
                    str(run.folder)], check=True, capture_output=True)
    figure.write_bytes((run.folder / "cylinder.png").read_bytes())
    headlines = [
        ("Plastic cylinder: elastic-plastic radius", "within 1 % of the classical solution at every plastic step",
         f"largest error {100 * worst:.2f} %", yes(worst <= 0.01)),
        ("Plastic cylinder: Newton to 98 % of p_L", "no cut-back, at most 8 iterations per step",
         f"{sum(iterations)} iterations, at most {max(iterations)} per step, {cutbacks} cut-back(s)",
         yes(cutbacks == 0 and max(iterations) <= 8)),
    ]
    collapse_text = "(quick mode: the run beyond p_L is left to `bash verification/plastic-cylinder/run.sh`)"
    if not ctx.quick:
        beyond = ctx.mfree_run("run", CYLINDER / "cylinder.toml", "plastic_cylinder_collapse",
                               ['constants.p="1.05 * pL"', "output.fields=[]"], expect_failure=True)
        converged = [line for line in beyond.stdout.splitlines() if "converged: load factor" in line]
        last = 1.05 * float(converged[-1].split("load factor")[1].split()[0]) if converged else float("nan")
        failed = not beyond.ok and "Newton gave up" in beyond.stderr
        headlines.append(("Plastic cylinder: collapse", "Newton gives up within 1 % above p_L",
                          f"last converged at {last:.4f} p_L, then {'gave up' if failed else 'did not give up'}",
                          yes(failed and 1.0 <= last <= 1.01)))
        collapse_text = (f"Pushed to 1.05 p_L, Newton converges up to {last:.4f} p_L and then "
                         f"{'gives up (exit status ' + str(beyond.returncode) + ')' if failed else 'does not give up'}.")
    md = f"""**Problem** ([{CYLINDER}/README.md](../{CYLINDER}/README.md)). A thick cylinder (a = 1, b = 2), perfectly
plastic von Mises (σ_y = 1), plane strain, small strain, E = 1000, ν = 0.49, under internal pressure
growing to 98 % of the limit load p_L = (2σ_y/√3) ln(b/a) by Newton with 17 load steps; quarter
annulus, slip on the axes, h = {0.1 if ctx.quick else 0.05}. The elastic-plastic radius c from the area of the plastic zone
(the quadrature points that have yielded) against Hill's p = (σ_y/√3)[2 ln(c/a) + 1 − c²/b²].

**Expected**: c within 1 % of the classical radius, Newton without cut-back; beyond p_L no solution
(displacement methods give an upper bound: the discrete collapse just above p_L).

**Observed:**

{table(["p / p_L", "u_r(a)", "c mfree", "c Hill", "error", "Newton", "cut-backs"], lines)}
{collapse_text}

{ctx.image(figure, "Plastic cylinder: load against inner displacement; elastic-plastic radius against Hill's")}
"""
    return Section("Plasticity: thick cylinder to the limit load", md, headlines)


# ---------------------------------------------------------------------------------------------
# Strip footing on Drucker–Prager soil

def strip_footing(ctx: Context) -> Section:
    h = 0.25 if ctx.quick else 0.1
    run = ctx.mfree_run("run", FOOTING / "footing.toml", "plastic_footing", [f"nodes.spacing={h}", "output.fields=[]"])
    rows = read_csv(run.folder / "load_steps.csv")
    lines = [[f"{0.98 * number(r['load_factor']):.4f}", f"{-number(r['probe_uy']):.4e}", f"{number(r['plastic_area']):.3f}",
              r["iterations"], r["cutbacks"]] for r in rows]
    iterations = [int(r["iterations"]) for r in rows]
    cutbacks = sum(int(r["cutbacks"]) for r in rows)
    headlines = [("Strip footing (Drucker–Prager): Newton to 98 % of q_u", "no cut-back, at most 10 iterations per step",
                  f"{sum(iterations)} iterations, at most {max(iterations)} per step, {cutbacks} cut-back(s)",
                  yes(cutbacks == 0 and max(iterations) <= 10))]
    collapse_text = "(quick mode: the run past q_u is left to `bash verification/plastic-footing/run.sh`)"
    if not ctx.quick:
        beyond = ctx.mfree_run("run", FOOTING / "footing.toml", "plastic_footing_collapse",
                               ['constants.q="1.1 * qu"', "output.fields=[]",
                                "newton.load_factors=[0.5, 0.8, 0.85, 0.88, 0.9, 0.92, 0.94, 0.96, 0.98, 1.0]"],
                               expect_failure=True)
        converged = [line for line in beyond.stdout.splitlines() if "converged: load factor" in line]
        last = 1.1 * float(converged[-1].split("load factor")[1].split()[0]) if converged else float("nan")
        failed = not beyond.ok and "Newton gave up" in beyond.stderr
        headlines.append(("Strip footing: collapse load", "Newton gives up within 5 % above Prandtl's q_u = c N_c",
                          f"last converged at {last:.4f} q_u", yes(failed and 1.0 <= last <= 1.05)))
        collapse_text = f"Pushed to 1.1 q_u, Newton converges up to {last:.4f} q_u and then gives up."
    md = f"""**Problem** ([{FOOTING}/README.md](../{FOOTING}/README.md)). A smooth strip load on a weightless soil, associative
Drucker–Prager matched to Mohr–Coulomb in plane strain (c = 10, φ = 20°), small strain, h = {h}; Newton with
load steps to 98 % of Prandtl's q_u = c N_c = 148.35.

**Expected**: convergence without cut-back to 0.98 q_u; past it, the discrete collapse load (an upper bound)
a few per cent above q_u.

**Observed** (settlement under the footing's centre; plastic area in m²):

{table(["q / q_u", "settlement", "plastic area", "Newton", "cut-backs"], lines)}
{collapse_text}
"""
    return Section("Plasticity: strip footing on Drucker–Prager soil", md, headlines)


# ---------------------------------------------------------------------------------------------
# MPM: Taylor bar

def taylor_bar(ctx: Context) -> Section:
    kinetic0 = 0.5 * 2700 * 0.032 * 0.008 * 200.0**2
    grids = [80] if ctx.quick else [80, 160]
    drifts, lines = [], []
    for cells in grids:
        run = ctx.mfree_run("run", TAYLOR_BAR / "bar.toml", f"taylor_bar/cells_{cells}",
                            [f"mpm.cells={cells}"] + (["dynamics.end_time=40e-6", "dynamics.frames=2"] if ctx.quick else []))
        e = read_csv(run.folder / "energy.csv")
        drift = max(abs(number(r["total"]) - kinetic0) for r in e) / kinetic0
        drifts.append(drift)
        p = read_csv(run.folder / "particles.csv")
        length = max(number(r["x"]) for r in p) / 0.032
        end = e[-1]
        lines.append([cells, f"{100 * drift:.2f} %", f"{number(end['kinetic']):.1f}", f"{number(end['strain']):.1f}",
                      f"{number(end['dissipated']):.1f}", f"{length:.3f}"])
    plot = script(ctx, TAYLOR_BAR / "plot.py")
    figure = ctx.figure("taylor_bar")
    argv = sys.argv
    sys.argv = ["plot.py", str(ctx.work / "taylor_bar")]
    try:
        plot.main()
    finally:
        sys.argv = argv
    figure.write_bytes((ctx.work / "taylor_bar" / "taylor_bar.png").read_bytes())
    falling = all(b < a for a, b in zip(drifts, drifts[1:]))
    headlines = [("MPM Taylor bar: energy balance", "kinetic + stored + dissipated within 1 % of the initial kinetic "
                  "energy, the drift falling with h", ", ".join(f"{100 * d:.2f} %" for d in drifts) + f" ({', '.join(map(str, grids))} cells)",
                  yes(max(drifts) <= 0.01 and falling))]
    md = f"""**Problem** ([{TAYLOR_BAR}/README.md](../{TAYLOR_BAR}/README.md)). A J2 aluminium bar (32 × 16 mm, the upper half
by symmetry) hits a fixed wall at 200 m/s; quadratic B-spline MPM, USL, 4 particles per cell. No work
is done on it: kinetic + stored + dissipated energy must stay {kinetic0:.0f} J/m.

**Observed** (energies in J/m at the end; L_f the final length):

{table(["cells", "drift", "kinetic", "stored", "dissipated", "L_f / L0"], lines)}
{ctx.image(figure, "Taylor bar: energies through time; final shape coloured by the equivalent plastic strain")}
"""
    return Section("Plasticity: MPM Taylor bar", md, headlines)


# ---------------------------------------------------------------------------------------------
# MPM: granular column collapse

def granular_collapse(ctx: Context) -> Section:
    runout = script(ctx, GRANULAR / "runout.py")
    ratios = [1.0] if ctx.quick else [0.5, 1.0, 2.0]
    extra = ["mpm.cells=160", "dynamics.end_time=0.8", "dynamics.frames=16"] if ctx.quick else []
    folder = ctx.work / "granular"
    for a in ratios:
        body = (f'body=[{{name = "column", shape = "rectangle", box = [[0.0, 0.0], [0.2, {0.2 * a:g}]], '
                f'material = "sand"}}]')
        ctx.mfree_run("run", GRANULAR / "column.toml", f"granular/a{a:g}", [body, 'output.fields=["velocity"]'] + extra)
    runs = sorted((runout.measure(str(f)) for f in sorted(folder.iterdir()) if (f / "particles.csv").exists()),
                  key=lambda m: m["a"])
    figure = ctx.figure("granular_collapse")
    runout.plot(runs, str(figure))
    lines, inside = [], []
    for m in runs:
        lube, laj = runout.law(runout.LUBE, m["a"]), runout.law(runout.LAJEUNESSE, m["a"])
        within = lube[0] <= m["runout"] <= 1.2 * laj[1]
        inside.append(within and abs(m["front_speed"]) < 0.05)
        lines.append([f"{m['a']:g}", f"{m['runout']:.2f}", runout.fmt_law(*lube), runout.fmt_law(*laj),
                      f"{m['front_speed']:.3f}", f"{m['height']:.2f}", f"{m['area']:.3f}"])
    headlines = [("MPM granular collapse: runout", "between Lube's law and 1.2 × Lajeunesse's (the experimental band "
                  "and 20 %), fronts stopped",
                  ", ".join(f"a = {m['a']:g}: {m['runout']:.2f}" for m in runs), yes(all(inside)))]
    md = f"""**Problem** ([{GRANULAR}/README.md](../{GRANULAR}/README.md)). A column of cohesionless sand (Drucker–Prager,
φ = 30°, ψ = 0, multiplicative finite strain), width L0 = 0.2 and height a L0, collapses under gravity
on a no-slip floor; quadratic B-spline MPM, USL, {'L0/h = 20 (quick)' if ctx.quick else 'L0/h = 30'}, 4 particles per cell. The final runout
(L∞ − L0)/L0 against the quasi-2D experimental laws: Lube et al. 2005 (sand, 1.2 a for a < 1.8,
1.9 a^(2/3) above 2.8) and Lajeunesse et al. 2005 (glass beads, 1.8 a for a < 3, 2.3 a^(2/3); the
prefactors as tabulated by Lagrée et al. 2011); the band between them is the experimental spread.

**Observed:**

{table(["a", "runout mfree", "Lube", "Lajeunesse", "front speed at the end [m/s]", "H∞ / L0", "area / L0 H0"], lines)}
The runout lies at the top of the band or above it (1.4–1.7 × Lube's, −9 % to +16 % of Lajeunesse's
at L0/h = 30); the README discusses why (a plane-strain cone matched to Mohr–Coulomb mobilises sin φ
rather than tan φ in simple shear; no rate dependence).

{ctx.image(figure, "Granular collapse: final deposits; runout against the aspect ratio with the experimental laws")}
"""
    return Section("Plasticity: MPM granular column collapse", md, headlines)
