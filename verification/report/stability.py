"""Stability stress tests: each drives one knob of a method towards (and past) the point where
it breaks, and records what the program does there: a converged answer, a growing error, or a
clear error message (never a NaN in an output file).

Every point is one `mfree run` of a verification scene with --set overrides; its numbers come
from the run's summary.json, its failure from the run's error message.

    cloud irregularity        lattice -> perturbed -> random nodes, three quadrature schemes
    support size              kernel support factor down to a singular moment matrix
    quadrature ratio          1 to 6 quadrature points per node, free-stiffness eigenvalues
    negative weights          quadratic RK quadrature weights on irregular clouds
    Nitsche penalty           beta from 1 to 1e4
    near incompressibility    nu from 0.3 to 0.4999 (volumetric locking), and past the limit
    MPM Courant number        per method and update scheme, to the empirical stability limit
    vibration amplitude       up to where det F of the exact motion approaches 0
    long runs                 ten periods, energy drift per method
    impact                    a wedge bouncing on a floor: energy through the impact
    Newton under growing load load steps, cut-backs, and the error when they run out
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from common import (CANTILEVER, LAME, LARGE_DEFORMATION, MPM_LONG, MPM_METHODS, MPM_VIBRATION, MPM_WEDGE, NITSCHE, QUIET,
                    VIBRATION,
                    Context, RunResult, Section, log_axes, new_figure, num, number, read_csv, save_figure, table)


MPM_UPDATES = ["usf", "usl", "szs", "usavg"]


def sections(ctx: Context) -> list[Section]:
    out = []
    for title, study in [("Cloud irregularity", cloud_irregularity),
                         ("Support size and the moment matrix", support_size),
                         ("Quadrature-to-node ratio and zero-energy modes", quadrature_ratio),
                         ("Quadratic RK: negative quadrature weights", negative_weights),
                         ("Nitsche penalty", nitsche_penalty),
                         ("Near incompressibility", incompressibility),
                         ("MPM Courant number", mpm_courant),
                         ("Vibration amplitude up to det F -> 0", amplitude),
                         ("Long runs: energy over ten periods", long_runs),
                         ("A body with free surfaces: energy through an impact", impact),
                         ("Newton under growing load", newton_load)]:
        with ctx.step(f"stability: {title}"):
            out.append(study(ctx, title))
    out.append(failure_modes(ctx))
    return out


# ---------------------------------------------------------------------------------------------
# Helpers


def message(run: RunResult) -> str:
    """The error message of a failed run, without the program's prefix."""
    lines = [line for line in run.stderr.strip().splitlines() if line.strip()]
    text = lines[-1] if lines else f"exit status {run.returncode}, no message"
    return text.removeprefix("mfree: error: ")


def short(text: str, limit: int = 110) -> str:
    return text if len(text) <= limit else text[:limit - 1] + "…"


_FAILURES: list[tuple[str, str]] = []  # (stress test, message) of every failed sweep point


def point(ctx: Context, test: str, subcommand: str, scene: Path, name: str, sets: list[str]) -> RunResult:
    """One sweep point; a failure is an observation, recorded for the failure-mode table."""
    run = ctx.mfree_run(subcommand, scene, name, sets, expect_failure=True)
    if not run.ok:
        _FAILURES.append((test, message(run)))
    return run


def scene_table(path: Path) -> dict:
    with open(path, "rb") as f:
        return tomllib.load(f)


def dilatational_wave_speed(scene: dict) -> float:
    """c_d = sqrt((lambda + 2 mu) / rho0) of the scene's material (an MPM scene's first [[material]]):
    the MPM Courant limit is h / c_d."""
    m = scene["material"][0] if isinstance(scene["material"], list) else scene["material"]
    e, nu, rho = m["youngs_modulus"], m["poisson_ratio"], m["density"]
    return math.sqrt(e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)


def first_error(run: RunResult, key: str = "displacement", index: int = 0) -> float:
    if not run.ok or not run.summary or len(run.summary.get("errors", [])) <= index:
        return math.nan
    value = run.summary["errors"][index].get(key)
    return math.nan if value is None else value


def value(run: RunResult, key: str) -> float:
    if not run.ok or not run.summary or run.summary.get(key) is None:
        return math.nan
    return run.summary[key]


# ---------------------------------------------------------------------------------------------
# Meshfree Galerkin


def cloud_irregularity(ctx: Context, title: str) -> Section:
    spacing = 1.5 if ctx.quick else 0.75
    perturbations = [0.0, 0.3] if ctx.quick else [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
    # The default (Gauss cells with VCI), the projected scheme, and the uncorrected baselines.
    variants = {"gauss_cells_vci": ["quadrature.scheme=gauss_cells"],
                "projected": ["quadrature.scheme=projected"],
                "gauss_cells": ["quadrature.scheme=gauss_cells", "quadrature.consistency=none", "quadrature.gauss_points=4"],
                "nodal": ["quadrature.scheme=nodal"]}
    schemes = list(variants)
    clouds = [(f"perturbed {p:g}", ["nodes.cloud=perturbed", f"nodes.perturbation={p}"]) for p in perturbations]
    clouds.append(("random", ["nodes.cloud=random"]))
    results = {}
    for label, cloud_sets in clouds:
        for scheme in schemes:
            name = f"stability/irregularity/{label.replace(' ', '_')}_{scheme}"
            results[label, scheme] = point(ctx, title, "run", CANTILEVER, name,
                                           QUIET + cloud_sets + [f"nodes.spacing={spacing}"] + variants[scheme])
    rows = []
    for label, _ in clouds:
        row = [label]
        for scheme in schemes:
            r = results[label, scheme]
            row += [value(r, "l2_displacement"), value(r, "energy")] if r.ok else ["failed: " + short(message(r), 40), "—"]
        rows.append(row)
    fig, (ax,) = new_figure()
    x = list(range(len(clouds)))
    for scheme in schemes:
        ax.plot(x, [value(results[c, scheme], "l2_displacement") for c, _ in clouds], "o-", label=scheme)
    ax.set_xticks(x, [c.replace("perturbed ", "") for c, _ in clouds])
    log_axes(ax, "node perturbation (fraction of the spacing); random", "relative L2 displacement error", log_x=False)
    ax.legend()
    figure = save_figure(fig, ctx.figure("stability_irregularity"))

    lattice = value(results[clouds[0][0], "projected"], "l2_displacement")
    worst = max(value(results[c, "projected"], "l2_displacement") for c, _ in clouds)
    ok = worst <= 3 * lattice
    body = (f"The Timoshenko cantilever (section 3) with linear RK at node spacing {spacing}, the nodes moved "
            f"from the lattice by uniform random offsets up to the given fraction of the spacing, and a "
            f"uniformly random cloud (seeded). Each column pair is one quadrature scheme: relative L2 "
            f"displacement and energy errors, measured by independent Gauss cells.\n\n"
            "Schemes: the default, 3 x 3 Gauss points per cell with VCI (`gauss_cells_vci`); the projected "
            "scheme with the symmetric correction; uncorrected Gauss cells (4 x 4 points) and nodal integration.\n\n"
            "Expected: the consistency-corrected quadratures stay as accurate on irregular clouds "
            "as on the lattice (they pass the patch test on any cloud); Gauss cells and nodal integration, "
            "not integration-consistent, lose accuracy as the cloud gets irregular.\n\n"
            + table(["cloud"] + [f"{s} {q}" for s in schemes for q in ("L2 u", "energy")], rows)
            + f"\nObserved: projected error from {num(lattice)} (lattice) to at most {num(worst)} "
            f"({worst / lattice:.1f}x); criterion: within 3x of the lattice.\n\n"
            + ctx.image(figure, "Cantilever error against cloud irregularity, per quadrature scheme")
            + f"\nReproduce one point: `{ctx.command('run', CANTILEVER, ['nodes.cloud=random', f'nodes.spacing={spacing}', 'quadrature.scheme=projected'])}`\n")
    return Section(title, body, [("Irregular clouds (projected quadrature)", "error within 3x of the lattice",
                                  f"{worst / lattice:.1f}x", "yes" if ok else "no")])


def support_size(ctx: Context, title: str) -> Section:
    spacing = 1.5
    factors = {"linear": [2.0, 1.5, 1.0, 0.75] if ctx.quick else [2.0, 1.75, 1.5, 1.25, 1.1, 1.0, 0.9, 0.75, 0.6],
               "quadratic": [3.0, 2.0, 1.25] if ctx.quick else [3.0, 2.5, 2.0, 1.75, 1.5, 1.25, 1.1]}
    clouds = {"lattice": ["nodes.cloud=lattice"], "perturbed 0.3": ["nodes.cloud=perturbed", "nodes.perturbation=0.3"]}
    rows, smallest, headlines = [], {}, []
    for order, fs in factors.items():
        for cloud, cloud_sets in clouds.items():
            for f in fs:
                name = f"stability/support/{order}_{cloud.split()[0]}_{f:g}"
                r = point(ctx, title, "run", CANTILEVER, name,
                          QUIET + cloud_sets + [f"nodes.spacing={spacing}", f"kernel.order={order}", f"kernel.factor={f}"])
                if r.ok:
                    smallest[order, cloud] = f
                rows.append([order, cloud, f, value(r, "l2_displacement") if r.ok else None,
                             value(r, "energy") if r.ok else None, "ok" if r.ok else short(message(r), 150)])
    limits = table(["RK order", "cloud", "smallest working factor"],
                   [[o, c, smallest.get((o, c), "none")] for o in factors for c in clouds])
    body = ("The cantilever at node spacing 1.5 with the support radius a = factor x h shrunk until the RK "
            "moment matrix M(x) = sum phi_a(x - x_I) p(x_I - x) p(x_I - x)^T becomes singular: a linear basis "
            "needs at least 3 neighbours not on one line inside the support of every point, a quadratic one "
            "at least 6 not on one conic. On a lattice with a circular support, factor 1 puts the nearest "
            "neighbours on the support's edge where the window vanishes.\n\n"
            "Expected: accuracy degrades gracefully as the support shrinks, then the run stops with an error "
            "naming the point, the neighbour count and the remedy (never a NaN).\n\n"
            + limits + "\n" + table(["RK order", "cloud", "factor", "L2 u", "energy", "outcome"], rows)
            + f"\nReproduce: `{ctx.command('run', CANTILEVER, ['nodes.spacing=1.5', 'kernel.factor=0.9'])}`\n")
    clear = all(r[5] == "ok" or "moment matrix" in r[5] for r in rows)
    headlines.append(("Support too small", "clear moment-matrix error",
                      "linear lattice works down to factor " + str(smallest.get(("linear", "lattice"), "none")),
                      "yes" if clear else "no"))
    return Section(title, body, headlines)


def quadrature_ratio(ctx: Context, title: str) -> Section:
    ratios = [1, 2, 4] if ctx.quick else [1, 1.5, 2, 3, 4, 5, 6]
    spacing = 3.0 if ctx.quick else 1.5
    count = 6
    runs = {}
    for cloud, sets in [("lattice", ["nodes.cloud=lattice"]), ("perturbed", ["nodes.cloud=perturbed"])]:
        for ratio in ratios:
            runs[cloud, f"projected, ratio {ratio:g}"] = point(
                ctx, title, "run", CANTILEVER, f"stability/ratio/{cloud}_{ratio:g}",
                QUIET + sets + [f"nodes.spacing={spacing}", f"quadrature.ratio={ratio}", f"output.eigenvalues={count}"])
        for scheme in ["nodal", "gauss_cells"]:
            runs[cloud, scheme] = point(ctx, title, "run", CANTILEVER, f"stability/ratio/{cloud}_{scheme}",
                                        QUIET + sets + [f"nodes.spacing={spacing}", f"quadrature.scheme={scheme}",
                                                        "quadrature.consistency=none", "quadrature.gauss_points=4",
                                                        f"output.eigenvalues={count}"])
    rows = []
    for (cloud, label), r in runs.items():
        if not r.ok:
            rows.append([cloud, label, "—", "failed: " + short(message(r))] + ["—"] * 4)
            continue
        lam = r.summary["smallest_eigenvalues"]
        rows.append([cloud, label, int(r.summary["quadrature_points"]), int(r.summary["zero_modes"]),
                     lam[3], lam[4], value(r, "l2_displacement"), value(r, "energy")])
    fig, (ax,) = new_figure()
    for cloud in ["lattice", "perturbed"]:
        pts = [(ratio, runs[cloud, f"projected, ratio {ratio:g}"]) for ratio in ratios]
        ax.plot([p for p, r in pts if r.ok], [r.summary["smallest_eigenvalues"][3] for p, r in pts if r.ok],
                "o-", label=f"projected, {cloud}")
        for scheme, marker in [("nodal", "s"), ("gauss_cells", "^")]:
            r = runs[cloud, scheme]
            if r.ok:
                ax.axhline(r.summary["smallest_eigenvalues"][3], ls=":", color="grey")
                ax.text(ratios[-1], r.summary["smallest_eigenvalues"][3], f" {scheme}, {cloud}", fontsize=7, va="bottom", ha="right")
    log_axes(ax, "quadrature points per node", "4th smallest eigenvalue / largest", log_x=False)
    ax.legend()
    figure = save_figure(fig, ctx.figure("stability_quadrature_ratio"))

    lattice = [(ratio, runs["lattice", f"projected, ratio {ratio:g}"]) for ratio in ratios]
    good = [r.summary["smallest_eigenvalues"][3] for _, r in lattice if r.ok]
    reference = max(good) if good else math.nan
    soft = [ratio for ratio, r in lattice if r.ok and r.summary["smallest_eigenvalues"][3] < 1e-2 * reference]
    spurious = [ratio for ratio, r in lattice if r.ok and r.summary["zero_modes"] > 3]
    observed = (f"near-zero-energy modes (4th eigenvalue below 1 % of its best value) at ratio "
                f"{', '.join(f'{s:g}' for s in soft)}" if soft else "no near-zero modes at any ratio")
    singular = [f"{cloud} ratio {label.split()[-1]}" for (cloud, label), r in runs.items()
                if not r.ok and label.startswith("projected")]
    if singular:
        observed += f"; singular stiffness (the solve refused) on {', '.join(singular)}"
    body = (f"Eigenvalues of the free stiffness K (no boundary conditions; 2 x nodes DOFs, dense solve) of the "
            f"cantilever at node spacing {spacing}, divided by the largest. A 2D body has exactly three zero "
            "eigenvalues, the rigid-body motions; each further zero is a spurious zero-energy mode (counted "
            "below 1e-8 of the largest), and a 4th eigenvalue orders of magnitude below its converged value is "
            "a near-zero-energy mode that the quadrature barely resists. The projected scheme at 1 to 6 "
            "quadrature points per node against nodal integration and Gauss cells.\n\n"
            "Expected (SPEC, seed 003): about 4 quadrature points per node in 2D are needed for stability; "
            "too few points under-integrate and admit (near-)zero-energy modes.\n\n"
            + table(["cloud", "scheme", "quadrature points", "zero modes", "lambda_4 / lambda_max",
                     "lambda_5 / lambda_max", "L2 u", "energy"], rows)
            + f"\nObserved on the lattice: {observed}; exact zero modes beyond the three rigid ones at ratio "
            f"{', '.join(f'{s:g}' for s in spurious) if spurious else 'none'}.\n\n"
            + ctx.image(figure, "Softest deformation mode against quadrature points per node")
            + f"\nReproduce: `{ctx.command('run', CANTILEVER, [f'nodes.spacing={spacing}', 'quadrature.ratio=1', 'output.eigenvalues=6'])}`\n")
    return Section(title, body, [("Quadrature ratio: zero-energy modes", "modes at too few points per node",
                                  observed, "—")])


def negative_weights(ctx: Context, title: str) -> Section:
    rows = []
    integration = ctx.work / "integration" / "integration.csv"
    if integration.exists():
        for r in read_csv(integration):
            if r["scheme"] == "rk" and r["function"] == "f1":
                rows.append([r["cloud"], r["order"], int(r["points"]), int(r["negative_weights"]),
                             number(r["most_negative"]), number(r["error"])])
    spacing = 1.5
    runs = []
    for cloud in ["perturbed", "random"]:
        for qcloud in ["lattice", "like_nodes"]:
            for order in ["linear", "quadratic"]:
                r = point(ctx, title, "run", CANTILEVER, f"stability/negative/{cloud}_{qcloud}_{order}",
                          QUIET + [f"nodes.cloud={cloud}", f"nodes.spacing={spacing}", f"quadrature.cloud={qcloud}",
                                   f"quadrature.order={order}"])
                runs.append([cloud, qcloud, order, int(value(r, "quadrature_points")) if r.ok else "—",
                             int(value(r, "negative_weights")) if r.ok else "—",
                             value(r, "most_negative_weight_relative"), value(r, "l2_displacement"),
                             value(r, "energy")] if r.ok else [cloud, qcloud, order, "failed: " + short(message(r))] + ["—"] * 4)
    negatives = sum(r[4] for r in runs if isinstance(r[4], int))
    refused = [r for r in runs if isinstance(r[3], str) and r[3].startswith("failed")]
    observed = (f"{negatives} negative weights in the cantilever runs that completed; {len(refused)} run(s) refused "
                "because a quadrature point got a weight <= 0 (its projected gradient divides by the weight)")
    body = ("Quadrature weights w_K = integral of phi_K (section 1's scheme) with linear and quadratic RK "
            "functions of the quadrature cloud. Quadratic RK functions take negative values, so on irregular "
            "clouds some weights are negative (SPEC section 3); a negative weight makes the quadrature of "
            "a positive energy indefinite, and the projected gradient of a point, a weighted average divided "
            "by its weight, is undefined there.\n\n"
            "Integration study, f1, scheme rk (weights of the quadrature cloud itself):\n\n"
            + (table(["cloud", "RK order", "points", "negative weights", "most negative", "error f1"], rows)
               if rows else "(integration study not run)\n")
            + "\nCantilever (spacing 1.5) with the quadrature cloud a lattice (the default) or of the node "
              "cloud's kind (`quadrature.cloud = like_nodes`), and linear or quadratic quadrature RK:\n\n"
            + table(["nodes", "quadrature cloud", "quadrature RK", "points", "negative weights",
                     "most negative / largest", "L2 u", "energy"], runs)
            + f"\nObserved: {observed}. The default (a lattice quadrature cloud with linear RK) has none.\n\n"
            + f"Reproduce: `{ctx.command('run', CANTILEVER, ['nodes.cloud=random', 'quadrature.cloud=like_nodes', 'quadrature.order=quadratic'])}`\n")
    integration_negative = sum(r[3] for r in rows if r[1] == "quadratic")
    return Section(title, body, [("Quadratic RK weights on irregular clouds", "some negative (SPEC 3)",
                                  f"{integration_negative} negative in the integration study; {len(refused)} "
                                  "cantilever run(s) refused with a clear error", "—")])


def nitsche_penalty(ctx: Context, title: str) -> Section:
    sets = ["study.spacings=[3.0, 1.5]"] if ctx.quick else []
    run = ctx.mfree_run("converge", NITSCHE, "stability/nitsche", sets)
    if not run.ok:
        return Section(title, f"The Nitsche sweep failed: {message(run)}\n", [])
    ctx.tolerate_failed_rows(run, "Nitsche penalty: a beta below the coercivity threshold gives an indefinite "
                                  "matrix, which the solver refuses (the row's errors are empty)")
    rows = read_csv(run.folder / "convergence.csv")
    spacings = sorted({number(r["spacing"]) for r in rows}, reverse=True)
    betas = sorted({number(r["beta"]) for r in rows})
    by = {(number(r["beta"]), number(r["spacing"])): r for r in rows}
    fig, (ax,) = new_figure()
    for h in spacings:
        ax.plot(betas, [number(by[b, h]["l2_displacement"]) for b in betas], "o-", label=f"L2 u, h = {h:g}")
        ax.plot(betas, [number(by[b, h]["energy"]) for b in betas], "s--", label=f"energy, h = {h:g}")
    log_axes(ax, "Nitsche penalty beta (penalty = beta M / h, M = lambda + 2 mu)", "relative error")
    ax.legend(fontsize=8)
    figure = save_figure(fig, ctx.figure("stability_nitsche"))
    table_rows = [[b] + [number(by[b, h][k]) for h in spacings for k in ("l2_displacement", "energy")] for b in betas]
    fine = spacings[-1]
    solved = [b for b in betas if not math.isnan(number(by[b, fine]["l2_displacement"]))]
    best = min(solved, key=lambda b: number(by[b, fine]["l2_displacement"]))
    refused = [f"beta = {b:g}, h = {h:g}" for b in betas for h in spacings if math.isnan(number(by[b, h]["l2_displacement"]))]
    body = ("The cantilever's clamped end imposed by Nitsche's method with penalty beta M / h (M = lambda + 2 mu, the P-wave modulus), beta swept over "
            "four decades (linear RK, lattice, projected quadrature). Nitsche's method is consistent, so the "
            "error should be insensitive to beta once beta exceeds the stability threshold (a multiple of the "
            "trace-inverse constant); a too small beta loses coercivity, a huge one makes it a plain penalty "
            "method and worsens conditioning.\n\n"
            + table(["beta"] + [f"{k}, h = {h:g}" for h in spacings for k in ("L2 u", "energy")], table_rows)
            + f"\nObserved: smallest displacement error at beta = {best:g} (h = {fine:g})"
            + (f"; not solvable (matrix not positive definite, refused by the solver): {', '.join(refused)}"
               if refused else "") + ".\n\n"
            + ctx.image(figure, "Cantilever errors against the Nitsche penalty")
            + f"\nReproduce: `{ctx.command('converge', NITSCHE)}`\n")
    return Section(title, body, [("Nitsche penalty", "plateau above the stability threshold",
                                  f"best beta = {best:g}", "—")])


# The largest Poisson's ratio a Galerkin scene accepts (galerkin/total_lagrangian.hpp,
# max_poisson_ratio): the sweep shows what happens up to it; one point past it must be refused.
NU_LIMIT = 0.49


def incompressibility(ctx: Context, title: str) -> Section:
    spacing = 0.2 if ctx.quick else 0.1
    ratios = [0.3, 0.49, 0.4999] if ctx.quick else [0.3, 0.4, 0.45, 0.49, 0.495, 0.499, 0.4999]
    orders = ["linear", "quadratic"]
    errors, rows = {}, []
    for order in orders:
        for nu in ratios:
            r = point(ctx, title, "run", LAME, f"stability/incompressible/{order}_{nu:g}",
                      QUIET + [f"nodes.spacing={spacing}", f"kernel.order={order}", f"constants.nu={nu}",
                               f"material.poisson_ratio={nu}", "material.allow_locking=true"]
                      + (["kernel.factor=3", "quadrature.consistency=vci"] if order == "quadratic" else []))
            errors[order, nu] = (value(r, "l2_displacement"), value(r, "energy"), value(r, "l2_stress"))
            rows.append([order, f"{nu:g}", f"{2 * nu / (1 - 2 * nu):.4g}"] + [e if r.ok else None for e in errors[order, nu]]
                        + ["ok" if r.ok else short(message(r), 150)])
    past = 0.495
    refused = point(ctx, title, "run", LAME, "stability/incompressible/past_limit",
                    QUIET + [f"nodes.spacing={spacing}", f"constants.nu={past}", f"material.poisson_ratio={past}"])
    clear = not refused.ok and refused.returncode == 1 and "incompressib" in message(refused)
    fig, (ax,) = new_figure()
    for order in orders:
        xs = [1 / (1 - 2 * nu) for nu in ratios]
        ax.plot(xs, [errors[order, nu][0] for nu in ratios], "o-", label=f"L2 u, {order} RK")
        ax.plot(xs, [errors[order, nu][1] for nu in ratios], "s--", label=f"energy, {order} RK")
        ax.plot(xs, [errors[order, nu][2] for nu in ratios], "^:", label=f"L2 stress, {order} RK")
    log_axes(ax, "1 / (1 - 2 nu)  (lambda / mu = 2 nu / (1 - 2 nu))", "relative error")
    ax.legend(fontsize=8)
    figure = save_figure(fig, ctx.figure("stability_incompressible"))
    base = errors["linear", ratios[0]][2]
    worst = errors["linear", ratios[-1]][2]
    body = ("The Lamé thick cylinder of section 'Lamé' (plane strain, internal pressure, exact solution as formulas) "
            f"at node spacing {spacing} with Poisson's ratio nu driven towards 1/2: lambda / mu = 2 nu / (1 - 2 nu) "
            "grows without bound, and a pure displacement formulation must represent a nearly divergence-free "
            "field with its trial functions: it locks (the error grows with lambda / mu) unless the functions "
            "can. Linear RK with the projected quadrature, quadratic RK (support 3h) with quadratic VCI; the "
            "Nitsche penalty scales with the P-wave modulus lambda + 2 mu, so the walls stay imposed as nu -> 1/2. "
            f"Points above nu = {NU_LIMIT:g} run with `material.allow_locking=true`.\n\n"
            + table(["RK order", "nu", "lambda / mu", "L2 u", "energy", "L2 stress", "outcome"],
                    rows)
            + f"\nObserved: linear RK's L2 stress error goes from {base:.3g} at nu = {ratios[0]:g} to {worst:.3g} at "
            f"nu = {ratios[-1]:g} ({worst / base:.3g} x). A Galerkin scene with nu above {NU_LIMIT:g} "
            f"(lambda / mu = {2 * NU_LIMIT / (1 - 2 * NU_LIMIT):.0f}) is refused unless it allows locking: nu = {past:g} gave "
            f"\"{short(message(refused), 200) if not refused.ok else 'no error (unexpected)'}\".\n\n"
            + ctx.image(figure, "Lamé errors against 1 / (1 - 2 nu)")
            + f"\nReproduce: `{ctx.command('run', LAME, ['constants.nu=0.499', 'material.poisson_ratio=0.499', 'material.allow_locking=true'])}`\n")
    return Section(title, body, [("Near incompressibility", f"locking shown; nu > {NU_LIMIT:g} refused clearly",
                                  f"linear L2 stress x{worst / base:.3g} from nu = {ratios[0]:g} to {ratios[-1]:g}",
                                  "yes" if clear else "no")])


# ---------------------------------------------------------------------------------------------
# MPM


def mpm_courant(ctx: Context, title: str) -> Section:
    scene = scene_table(ctx.root / MPM_VIBRATION)
    c = dilatational_wave_speed(scene)
    amplitude = scene["exact"]["amplitude"]
    cells, ppc = 16, 9
    h = 1.0 / cells
    if ctx.quick:
        methods, updates, courants, periods = ["bspline", "cpdi"], ["usf", "usl"], [0.5, 1.5], 1
    else:
        methods, updates, courants, periods = MPM_METHODS, MPM_UPDATES, [0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0], 3
    end = 0.02 * periods
    results = {}
    for m in methods:
        for u in updates:
            for cn in courants:
                dt = cn * h / c
                results[m, u, cn] = point(
                    ctx, title, "run", MPM_VIBRATION, f"stability/courant/{m}_{u}_{cn:g}",
                    QUIET + [f"mpm.method={m}", f"mpm.update={u}", f"mpm.cells={cells}", f"mpm.particles_per_cell={ppc}",
                             # dt = min(time_step, courant h / c_d): both set to the point's C
                             f"dynamics.time_step={dt:.9e}", f"dynamics.courant={cn}",
                             f"dynamics.end_time={end}", "dynamics.frames=0",
                             "dynamics.error_times=[1.0]", "dynamics.energy_every=10",
                             f"dynamics.allow_unstable_time_step={'true' if cn > 1 else 'false'}"])

    def stable(r: RunResult) -> bool:
        return r.ok and first_error(r) < amplitude

    rows, limits = [], {}
    for m in methods:
        for u in updates:
            ok = [cn for cn in courants if stable(results[m, u, cn])]
            # The empirical limit: the largest Courant number below which every tested one is stable.
            limit = None
            for cn in courants:
                if not stable(results[m, u, cn]):
                    break
                limit = cn
            limits[m, u] = limit
            first_bad = next((results[m, u, cn] for cn in courants if not stable(results[m, u, cn])), None)
            why = "—" if first_bad is None else (
                short(message(first_bad), 90) if not first_bad.ok else f"error {num(first_error(first_bad))} m > A")
            rows.append([m, u, "none" if limit is None else f"{limit:g}",
                         ", ".join(f"{x:g}" for x in ok) or "none", why])
    err_rows = [[f"{m} {u}"] + [first_error(results[m, u, cn]) / amplitude if results[m, u, cn].ok else "failed"
                                for cn in courants] for m in methods for u in updates]
    fig, axes = new_figure(len(updates), width=4.5)
    for ax, u in zip(axes, updates):
        for m in methods:
            ys = [first_error(results[m, u, cn]) / amplitude for cn in courants]
            ax.plot(courants, ys, "o-", label=m)
        ax.axhline(1.0, color="k", lw=0.8, ls=":")
        ax.set_title(u.upper())
        log_axes(ax, "Courant number dt c_d / h", f"relative RMS u error after {periods} period(s)", log_x=False)
    axes[0].legend(fontsize=7)
    figure = save_figure(fig, ctx.figure("stability_mpm_courant"))
    usf = {m: limits[m, "usf"] for m in methods}
    body = (f"The MPM vibration problem (A = {amplitude}, {cells} cells, {ppc} particles per cell) run for "
            f"{periods} period(s) at time steps dt = C h / c_d, c_d = {c:.1f} m/s the dilatational wave speed, "
            f"for Courant numbers C from {courants[0]} to {courants[-1]} "
            "(allow_unstable_time_step = true above 1). A run is stable when it completes and its RMS "
            f"displacement error at the end is below the amplitude A = {amplitude} m (an unstable run grows "
            "without bound or stops with an error naming the particle and time).\n\n"
            "Expected: explicit MPM is stable up to C of order 1 (the grid's CFL limit); shape functions "
            "with wider support (B-splines) and the update scheme shift it.\n\n"
            "Empirical stability limit (the largest tested C with every smaller one stable):\n\n"
            + table(["method", "update", "limit C", "stable at", "first unstable point"], rows)
            + "\nRelative RMS displacement error (error / A) at the end, per Courant number:\n\n"
            + table(["method update"] + [f"C = {cn:g}" for cn in courants], err_rows)
            + "\n" + ctx.image(figure, "MPM error after the run against the Courant number, per update scheme")
            + f"\nReproduce one point: `{ctx.command('run', MPM_VIBRATION, ['mpm.method=cpdi', 'mpm.cells=16', f'dynamics.time_step={1.2 * h / c:.4e}', 'dynamics.courant=1.2', 'dynamics.allow_unstable_time_step=true'])}`\n")
    return Section(title, body, [("MPM Courant limit (USF)", "C of order 1",
                                  ", ".join(f"{m} {'none' if v is None else f'{v:g}'}" for m, v in usf.items()), "—")])


def amplitude(ctx: Context, title: str) -> Section:
    amplitudes = [0.05, 0.15] if ctx.quick else [0.05, 0.1, 0.125, 0.14, 0.15, 0.155, 0.158]
    methods = ["bspline", "cpdi"] if ctx.quick else MPM_METHODS
    cells, ppc, dt = 16, 9, 4e-5
    rows, outcome = [], {}
    for a in amplitudes:
        jmin = (1 - 2 * math.pi * a) ** 2
        row = [a, jmin]
        r = point(ctx, title, "run", VIBRATION, f"stability/amplitude/meshfree_{a:g}",
                  QUIET + [f"exact.amplitude={a}", "nodes.spacing=0.0625", "dynamics.end_time=0.02", "dynamics.frames=0",
                           "dynamics.error_times=[0.25, 1.0]"])
        outcome["meshfree TL", a] = r
        for m in methods:
            outcome[m, a] = point(ctx, title, "run", MPM_VIBRATION, f"stability/amplitude/{m}_{a:g}",
                                  QUIET + [f"exact.amplitude={a}", f"mpm.method={m}", f"mpm.cells={cells}",
                                           f"mpm.particles_per_cell={ppc}", f"dynamics.time_step={dt}",
                                           "dynamics.end_time=0.02", "dynamics.frames=0", "dynamics.error_times=[0.25, 1.0]"])
        for label in ["meshfree TL"] + methods:
            r = outcome[label, a]
            row.append(first_error(r, index=1) / a if r.ok else "failed")
        rows.append(row)
    failures = [[label, a, short(message(r), 140)] for (label, a), r in outcome.items() if not r.ok]
    body = ("The vibration problem of sections 5 and 6 at growing amplitude A, one period. The exact motion "
            "has det F = (1 + 2 pi A cos(2 pi X) sin(c pi t)) (1 - 2 pi A cos(2 pi Y) sin(c pi t)), whose minimum "
            "(1 - 2 pi A)^2 reaches 0 at A = 1/(2 pi) = 0.159. Total-Lagrangian meshfree (central differences, "
            f"h = 1/16) and every MPM method ({cells} cells, {ppc} particles per cell, dt = {dt:g} s, USF); "
            "relative RMS displacement error at t = T (error / A), or the run's failure.\n\n"
            "Expected: errors grow as det F -> 0; a run that inverts a particle or quadrature point (J <= 0) "
            "stops with an error naming the point, its position and the time.\n\n"
            + table(["A", "min det F (exact)", "meshfree TL"] + methods, rows)
            + ("\nFailures, as the program reported them:\n\n" + table(["method", "A", "message"], failures)
               if failures else "\nNo run failed.\n")
            + f"\nReproduce one point: `{ctx.command('run', MPM_VIBRATION, ['exact.amplitude=0.15', 'mpm.method=cpdi'])}`\n")
    survivors = [label for label in ["meshfree TL"] + methods if outcome[label, amplitudes[-1]].ok]
    return Section(title, body, [("Amplitude up to det F -> 0", "clear J <= 0 errors, no NaN",
                                  f"at A = {amplitudes[-1]}: {', '.join(survivors) or 'none'} complete", "—")])


def long_runs(ctx: Context, title: str) -> Section:
    sets = (["dynamics.end_time=0.04", "dynamics.error_times=[1.0]", "study.methods=[\"bspline\", \"cpdi\"]",
             "dynamics.frames=0", "output.fields=[]"] if ctx.quick else ["dynamics.frames=0", "output.fields=[]"])
    # The USF runs of every method; Verlet for B-splines and lCPDI; MLS (linear basis) with the
    # seed's USL and with Verlet; MLS with the quadratic basis, USL and Verlet, under both mappings,
    # and mls.toml's configuration (Verlet, the pseudo-inverse with the short-wave mass filter).
    variants = [("", "stability/long_mpm", []),
                ("", "stability/long_mpm_verlet", ['study.methods=["bspline", "cpdi"]', 'study.updates=["verlet"]']),
                ("", "stability/long_mpm_mls", ['study.methods=["bspline_mls"]', 'study.updates=["usl", "verlet"]']),
                ("quadratic MLS, ", "stability/long_mpm_mls_quadratic",
                 ['mpm.method="bspline_mls"', 'study.methods=["bspline_mls"]', 'mpm.mls_basis="quadratic"',
                  'study.updates=["usl", "verlet"]', 'study.mappings=["lumped", "pseudo_inverse"]']),
                ("quadratic MLS, mass_filter 0.3, ", "stability/long_mpm_mls_filtered",
                 ['mpm.method="bspline_mls"', 'study.methods=["bspline_mls"]', 'mpm.mls_basis="quadratic"',
                  'mpm.update="verlet"', 'mpm.mapping="pseudo_inverse"', 'mpm.mass_filter=0.3'])]
    if ctx.quick:
        variants = variants[:1]
    mpm_runs = []
    for basis, name, extra in variants:
        run = ctx.mfree_run("converge", MPM_LONG, name, sets + extra)
        ctx.tolerate_failed_rows(run, "MPM runs that fail within ten periods are recorded with their message")
        mpm_runs.append((basis, run, extra))
    scene = scene_table(ctx.root / MPM_LONG)
    a = scene["exact"]["amplitude"]
    end = 0.04 if ctx.quick else scene["dynamics"]["end_time"]
    meshfree = {}
    for scheme, dt in [("central_difference", 1e-5), ("newmark", 2.5e-5)]:
        meshfree[scheme] = point(ctx, title, "run", VIBRATION, f"stability/long_{scheme}",
                                 QUIET + [f"exact.amplitude={a}", "nodes.spacing=0.0625", f"dynamics.scheme={scheme}",
                                          f"dynamics.time_step={dt}", f"dynamics.end_time={end}", "dynamics.frames=0",
                                          "dynamics.error_times=[1.0]", "dynamics.energy_every=20"])
    rows, curves = [], []
    for basis, mpm, _ in mpm_runs:
        if not mpm.ok:
            continue
        for r in read_csv(mpm.folder / "mpm_convergence.csv"):
            if number(r["time_fraction"]) == 1.0 or r["status"] != "ok":
                rows.append([f"MPM {r['method']} ({basis}{r['update']}, {r['mapping']})",
                             r["status"] if r["status"] == "ok" else short(r["status"], 90),
                             number(r["displacement"]) / a, number(r["energy_drift"]), number(r["seconds"])])
        energy = mpm.folder / "mpm_energy.csv"
        if energy.exists():
            series = {}
            for r in read_csv(energy):
                label = f"MPM {r['method']} ({basis}{r['update']}, {r['mapping']})"
                series.setdefault(label, []).append((number(r["time"]), number(r["total"])))
            curves += list(series.items())
    for scheme, r in meshfree.items():
        rows.append([f"meshfree TL {scheme}", "ok" if r.ok else short(message(r), 90),
                     first_error(r) / a, value(r, "energy_drift"), r.seconds])
        if r.ok and (r.folder / "energy.csv").exists():
            curves.append((f"meshfree TL {scheme}", [(number(e["time"]), number(e["total"]))
                                                     for e in read_csv(r.folder / "energy.csv")]))
    fig, (ax,) = new_figure(width=7)
    for label, pts in curves:
        t0 = pts[0][1]
        ax.plot([p[0] / 0.02 for p in pts], [p[1] - t0 for p in pts], label=label)
    ax.set_xlabel("time / period")
    ax.set_ylabel("E(t) - E(0) [J/m]: kinetic + strain - work of body forces")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    figure = save_figure(fig, ctx.figure("stability_long_runs"))
    body = (f"The vibration problem at A = {a} for {end / 0.02:g} periods: every MPM method (16 cells, 9 particles "
            "per cell, dt = 1e-5 s, USF; velocity Verlet for quadratic B-splines and lCPDI; MLS with the seed's "
            "USL and with Verlet, with the linear and the quadratic basis, the latter under the lumped and the "
            "pseudo-inverse mapping, and the pseudo-inverse with mls.toml's short-wave mass filter) and the "
            "total-Lagrangian meshfree solver (h = 1/16, central differences "
            "dt = 1e-5 s and Newmark's trapezoidal rule dt = 2.5e-5 s). Energy balance E = kinetic + strain - "
            "work of the body forces, constant for the exact motion; drift = max |E(t) - E(0)| / max (kinetic + "
            "strain).\n\n"
            "Expected: Newmark's trapezoidal rule conserves energy up to the Newton tolerance; central "
            "differences conserve a shadow energy (bounded oscillation); MPM with the symplectic Euler "
            "updates (USF, USL) drifts at first order in dt, velocity Verlet holds the balance to second order "
            "(the body forces' work integrated to the update's order), MLS reconstruction gains energy (its "
            "Gauss-point forces are not the derivative of the particles' stored energy) and its errors grow to the "
            "size of the motion, except with the short-wave mass filter, which holds the grid's short modes "
            "(the error at 10 T below plain B-splines'), and a method that goes unstable stops with an error.\n\n"
            + table(["method", "status", "relative u error at the end", "energy drift", "seconds"], rows)
            + "\n" + ctx.image(figure, "Energy balance through the long runs")
            + "\nReproduce:\n\n```sh\n" + "\n".join(ctx.command("converge", MPM_LONG, extra) for _, _, extra in mpm_runs)
            + "\n```\n")
    drift = {row[0]: row[3] for row in rows}
    return Section(title, body, [("Long runs: energy drift", "bounded for stable methods",
                                  "; ".join(f"{k} {num(v, 2)}" for k, v in drift.items()), "—")])


def impact(ctx: Context, title: str) -> Section:
    """The wedge of wedge_impact.toml bouncing on a slip floor: kinetic + strain against the
    initial kinetic energy + the work of gravity, per method, update and mapping."""
    end = 0.3 if ctx.quick else 0.8
    variants = [("bspline", "usf", "lumped", []), ("bspline", "verlet", "lumped", []), ("bspline", "usl", "lumped", []),
                ("cpdi", "usf", "lumped", []), ("bspline_cubic", "verlet", "lumped", []),
                ("bspline", "verlet", "pseudo_inverse", []), ("bspline_cubic", "verlet", "pseudo_inverse", []),
                ("cpdi", "verlet", "pseudo_inverse", []),
                ("bspline_mls", "usf", "lumped", []), ("bspline_mls", "verlet", "lumped", []),
                ("bspline_mls", "usl", "lumped", []),
                ("bspline_mls", "verlet", "pseudo_inverse", ["mpm.mls_basis=\"quadratic\""])]
    if ctx.quick:  # a conservative, a dissipative and an MLS variant: the machinery, not the verdict
        variants = [variants[k] for k in (0, 2, 7, 9)]
    rows, curves, ratios = [], [], {}
    for method, update, mapping, extra in variants:
        label = f"{method} ({update}, {mapping}{', quadratic MLS' if extra else ''})"
        sets = QUIET + [f"mpm.method={method}", f"mpm.update={update}", f"mpm.mapping={mapping}",
                        f"dynamics.end_time={end}", "dynamics.frames=0", "dynamics.energy_every=10"] + extra
        r = point(ctx, title, "run", MPM_WEDGE, f"stability/impact/{method}_{update}_{mapping}", sets)
        if not r.ok or not (r.folder / "energy.csv").exists():
            rows.append([label, short(message(r), 90), "—", "—", "—", "—"])
            continue
        records = read_csv(r.folder / "energy.csv")
        k0 = number(records[0]["kinetic"])
        series = [(number(e["time"]), (number(e["kinetic"]) + number(e["strain"]))
                   / (k0 + number(e["external_work"]))) for e in records]
        at_03 = min(series, key=lambda p: abs(p[0] - 0.3))[1]
        ratios[label] = series[-1][1]
        curves.append((label, series))
        warned = "yes" if "warning: the energy balance grew" in r.stderr else "no"
        rows.append([label, "ok", f"{at_03:.3f}", f"{series[-1][1]:.3f}", value(r, "energy_growth"), warned])
    fig, (ax,) = new_figure(width=7)
    for label, pts in curves:
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "--" if label.startswith("bspline_mls") else "-",
                label=label, lw=1)
    ax.set_xlabel("t [s] (the wedge reaches the floor at 0.18 s)")
    ax.set_ylabel("(kinetic + strain) / (initial kinetic + work of gravity)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6)
    figure = save_figure(fig, ctx.figure("stability_impact"))
    body = (f"`{MPM_WEDGE}`: a rubber wedge (Neo-Hookean, E = 2e5 Pa) falls at 0.5 m/s under gravity onto "
            "a slip floor, 32 cells, 9 particles per cell, dt = 2e-4 s, to t = "
            f"{end:g} s. No exact solution: kinetic + strain must equal the initial kinetic energy plus the work of "
            "gravity (ratio 1; a dissipative scheme falls below). `mfree run` warns when the energy balance has grown "
            "by more than 5 % of the largest kinetic + strain (column 'growth').\n\n"
            "Expected: plain B-splines and CPDI with USF or Verlet keep the ratio within a few per cent, with either "
            "mapping; USL dissipates. MLS reconstruction integrates with Gauss points only in the interior cells "
            "(the particles of the cells along the free surfaces are their own quadrature points) and keeps the "
            "balance through the impact (0.3 s), but its force is not the derivative of the particles' stored energy "
            "and the bouncing body gains energy later (verification/mpm-vibration/README.md, \"Bodies that do not "
            "fill the grid\").\n\n"
            + ("In quick mode four of the twelve variants run.\n\n" if ctx.quick else "")
            + table(["method (update, mapping)", "status", "ratio at 0.3 s", f"ratio at {end:g} s", "growth",
                     "warned"], rows)
            + "\n" + ctx.image(figure, "Energy ratio of the bouncing wedge")
            + "\nReproduce (one row):\n\n```sh\n"
            + ctx.command("run", MPM_WEDGE, ["mpm.method=bspline_mls", "mpm.update=usf", f"dynamics.end_time={end}"])
            + "\n```\n")
    conservative = [k for k in ratios if not k.startswith("bspline_mls") and "usl" not in k]
    worst = max((abs(ratios[k] - 1.0) for k in conservative), default=math.nan)
    mls = [ratios[k] for k in ratios if k.startswith("bspline_mls") and "usl" not in k]
    return Section(title, body, [
        ("Impact: energy of plain B-splines and CPDI (USF, Verlet; both mappings)", "within 5 % of the energy put in",
         f"largest |ratio - 1| {num(worst, 2)} at {end:g} s", "yes" if worst <= 0.05 else "no"),
        ("Impact: energy of MLS reconstruction (USF, Verlet)", "within 5 % of the energy put in",
         "ratios " + ", ".join(num(v, 3) for v in mls) + f" at {end:g} s",
         "yes" if mls and max(abs(v - 1.0) for v in mls) <= 0.05 else "no")])


# ---------------------------------------------------------------------------------------------
# Newton


def newton_load(ctx: Context, title: str) -> Section:
    scene = scene_table(ctx.root / LARGE_DEFORMATION)
    load = scene["exact"]["load"]
    spacing = 1.5 if ctx.quick else 0.75
    scales = [1, 2] if ctx.quick else [0.5, 1, 2, 4, 8]
    base = QUIET + [f"nodes.spacing={spacing}", "newton.load_factors=[0.5, 1.0]",
                    "newton.max_iterations=6", "newton.line_search=false"]
    rows = []
    cases = [(f"P = {s:g} x {load:g}", base + [f"exact.load={s * load}"]) for s in scales]
    cases.append((f"P = {load:g}, one step, no cut-backs allowed",
                  QUIET + [f"nodes.spacing={spacing}", "newton.load_factors=[1.0]", "newton.max_iterations=6",
                           "newton.line_search=false", "newton.max_cutbacks=0"]))
    for i, (label, sets) in enumerate(cases):
        r = point(ctx, title, "run", LARGE_DEFORMATION, f"stability/newton_{i}", sets)
        if r.ok:
            steps = r.summary["load_steps"]
            csv = read_csv(r.folder / "load_steps.csv")
            rows.append([label, "converged", len(steps), int(sum(s["iterations"] for s in steps)),
                         int(sum(s["cutbacks"] for s in steps)), number(csv[-1]["probe_uy"]),
                         number(csv[-1]["probe_uy"]) / 48.0])
        else:
            rows.append([label, short(message(r), 160), "—", "—", "—", "—", "—"])
    body = ("The Neo-Hookean cantilever of section 4 under end loads growing to several times the one that "
            "bends it to 43 % of its length, with two load steps (0.5 and 1 of the load), Newton "
            "without line search and at most 6 iterations per step: a step that does not converge is halved "
            "(cut back) and retried, up to max_cutbacks times. The last case allows no cut-back.\n\n"
            "Expected: larger loads need more cut-backs and iterations but converge; when cut-backs run out "
            "the run stops with an error naming the load factor and the remedy (never a NaN).\n\n"
            + table(["load", "outcome", "load steps", "Newton iterations", "cut-backs", "tip u_y", "u_y / L"], rows)
            + f"\nReproduce: `{ctx.command('run', LARGE_DEFORMATION, ['newton.load_factors=[1.0]', 'newton.max_iterations=6', 'newton.line_search=false'])}`\n")
    cut = sum(r[4] for r in rows if isinstance(r[4], int))
    return Section(title, body, [("Newton with cut-backs", "converges under growing load; clear error otherwise",
                                  f"{cut} cut-backs over {len(scales)} loads", "—")])


def failure_modes(ctx: Context) -> Section:
    kinds = {}
    for test, text in _FAILURES:
        kinds.setdefault((test, short(text, 160)), 0)
        kinds[test, short(text, 160)] += 1
    rows = [[test, count, text] for (test, text), count in sorted(kinds.items())]
    nan_free = all("nan" not in text.lower() for _, text in _FAILURES)
    body = ("Every sweep point above that did not complete, with the message the program printed (stderr, exit "
            "status 1). None of these runs left a NaN in an output file: the report scans every CSV and "
            "summary.json it produced and fails when it finds one (see the header).\n\n"
            + (table(["stress test", "runs", "message"], rows) if rows else "No sweep point failed.\n"))
    return Section("Failure modes", body, [("Failures end in a clear error", "message, exit 1, no NaN output",
                                            f"{len(_FAILURES)} failed points, {len(rows)} distinct messages",
                                            "yes" if nan_free else "no")])
