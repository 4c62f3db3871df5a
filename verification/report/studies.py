"""Convergence studies of the verification report: integration accuracy, patch tests, the
cantilever (small and large deformation), the vibration problem with the meshfree method and
with every MPM method, and error against run time.

Each study runs mfree once, reads its CSV, compares observed rates with the expected ones of
the study's README and returns one Section. Results that another section reuses (the
cantilever, vibration and MPM tables feed the error-against-time section) are kept in
ctx.data, so no study runs twice.

Rate criterion, unless a study says otherwise: the observed rate between the two finest
levels is at least the expected one minus 0.3.
"""
from __future__ import annotations

import math
import re
import tomllib
import traceback
from collections import defaultdict
from pathlib import Path

from common import (CANTILEVER, LARGE_DEFORMATION, MPM_METHODS, MPM_VIBRATION, VIBRATION, Context, Section, fastest, legend_outside, level_ticks, log_axes, new_figure, num, number,
                    rate, rate_text, read_csv, save_figure, seconds_text, slope_guide, table)

TOLERANCE = 0.3  # observed rate >= expected - TOLERANCE
PATCH_TOLERANCE = 1e-10  # relative L2 displacement error of a passed patch test
TARGETS = (1e-2, 1e-3, 1e-4)  # relative errors of the work-precision tables

INTEGRATION = Path("verification/integration")
PATCH_TEST = Path("verification/report/patch_test.toml")

VIBRATION_QUICK = ["study.spacings=[0.25,0.125]", "study.time_step_check=false",
                   "dynamics.end_time=0.005", "dynamics.error_times=[1.0]"]
# The report keeps to 30 minutes on 2 cores: the dt / 2 rerun of the finest level (3.5 min) is
# left to verification/vibration/run.sh, whose README gives its result.
VIBRATION_FULL = ["study.time_step_check=false"]
MPM_FULL = ["study.particles_per_cell=[9]"]
MPM_QUICK = ["study.cells=[8,16]", "study.particles_per_cell=[4]",
             "dynamics.end_time=0.005", "dynamics.error_times=[1.0]"]
CANTILEVER_QUICK = ["study.spacings=[6.0,3.0]"]
# Quadratic RK with quadratic VCI (test-gradient correction of the RK order), beside the
# default symmetric correction, which restores linear consistency only.
QUADRATIC_VCI = ['study.orders=["quadratic"]', 'study.schemes=["projected"]', "quadrature.consistency=vci"]
# The quadratic patch test: the patch-test scene with a quadratic exact field (linear stress,
# constant body force).
QUADRATIC_PATCH = ["exact.solution=quadratic", "exact.hessian_x=[[0.0008,-0.0003],[-0.0003,0.0005]]",
                   "exact.hessian_y=[[-0.0004,0.0006],[0.0006,0.0011]]", 'study.orders=["quadratic"]',
                   'study.schemes=["projected"]']

# Gauss cells without a correction as the literature's baseline: 4 x 4 points per cell for
# linear RK, 6 x 6 for quadratic (the scene default is 3 x 3 with VCI).
GAUSS_BASELINE = ['study.schemes=["gauss_cells"]', "quadrature.consistency=none", "quadrature.gauss_points=4",
                  "study.quadratic_gauss_points=6"]
# One level finer on the perturbed cloud for the Gauss-cell schemes alone (with and without
# VCI), so that the work-precision duel there reaches an energy error of 1e-4.
PERTURBED_FINE = ["study.spacings=[0.1875]", 'study.clouds=["perturbed"]', 'study.schemes=["gauss_cells"]']

QUADRATURES = ["gauss_cells_vci", "projected", "projected_vci", "gauss_cells", "nodal"]
QUADRATURE_NAMES = {"projected_vci": "projected + VCI", "gauss_cells_vci": "Gauss cells + VCI"}
# Schemes that pass the patch test to round-off on every cloud (section 2).
CONSISTENT = ("gauss_cells_vci", "projected", "projected_vci")


def method_label(row: dict) -> dict:
    """The row with its scheme named after the scheme and the correction: the scheme alone for its
    usual form (projected with the symmetric correction, Gauss cells and nodal without one),
    scheme_correction otherwise (gauss_cells_vci, projected_vci)."""
    scheme, fix = row["scheme"], row.get("consistency", "none")
    usual = fix == "none" or (scheme == "projected" and fix == "symmetric")
    return dict(row, scheme=scheme if usual else f"{scheme}_{fix}")
INTEGRATION_SCHEMES = ["rk linear", "rk quadratic", "voronoi", "gauss_cells", "equal"]
CLOUD_STYLE = {"lattice": "-", "perturbed": "--", "random": ":", "-": "-."}
CLOUD_MARK = {"lattice": "o", "perturbed": "s", "random": "^", "-": "x"}


def sections(ctx: Context) -> list[Section]:
    """The convergence and work-precision sections, in report order."""
    studies = [("Integration accuracy", integration_accuracy),
               ("Patch tests", patch_tests),
               ("Cantilever, small deformation", cantilever_small),
               ("Cantilever, large deformation", cantilever_large),
               ("Meshfree vibration", meshfree_vibration),
               ("MPM vibration", mpm_vibration),
               ("MPM vibration: time update, mapping and MLS", mpm_options),
               ("Work-precision: error against run time", work_precision)]
    return [run_study(ctx, title, study) for title, study in studies]


def run_study(ctx: Context, title: str, study) -> Section:
    """Runs one study, timed; a study that raises becomes a section saying what went wrong."""
    with ctx.step(title):
        try:
            section = study(ctx)
        except Exception as e:  # noqa: BLE001 - one broken study must not hide the others
            ctx.failures.append(f"{title}: the study could not be completed ({type(e).__name__}: {e})")
            traceback.print_exc()
            section = Section(title, f"**The study could not be completed**: `{type(e).__name__}: {e}`.\n"
                                     "See the failures listed in the header.\n",
                              [(title, "study completes", "failed", "no")])
    section.title = title
    return section


# ---------------------------------------------------------------------------------------------
# Helpers


def group(rows: list[dict], keys: tuple[str, ...], order_by: str, descending: bool = False,
          key_order=None) -> dict:
    """Rows grouped by the values of `keys`, each group sorted by the number in `order_by`; the
    groups in the order of `key_order(key)` (default: alphabetical)."""
    groups = defaultdict(list)
    for r in rows:
        groups[tuple(r[k] for k in keys)].append(r)
    keys_sorted = sorted(groups, key=key_order) if key_order else sorted(groups)
    return {k: sorted(groups[k], key=lambda r: number(r[order_by]), reverse=descending) for k in keys_sorted}


def position(name: str, names: list[str]) -> int:
    """The place of `name` in a list of known names; unknown names last."""
    return names.index(name) if name in names else len(names)


def quadrature_order(key: tuple) -> tuple:
    """(cloud, order, scheme) keys: by cloud, then RK order, then projected, Gauss cells, nodal."""
    cloud, order, scheme = key
    return cloud, order, position(scheme, QUADRATURES)


def series_rates(rows: list[dict], error: str, size: str = "spacing") -> list[float]:
    """Observed rates between consecutive rows (sorted coarse to fine) of one series."""
    return [rate(number(a[error]), number(b[error]), number(a[size]), number(b[size]))
            for a, b in zip(rows, rows[1:])]


def last_rate(rows: list[dict], error: str, size: str = "spacing") -> float:
    """The observed rate between the two finest rows of a series (nan with fewer than two)."""
    rates = series_rates(rows, error, size)
    return rates[-1] if rates else math.nan


def meets(observed: float, expected: float) -> bool:
    """The rate criterion of the report: observed >= expected - TOLERANCE."""
    return not math.isnan(observed) and observed >= expected - TOLERANCE


def verdict(flags: list[bool | None]) -> str:
    """"yes" when every checked flag holds, "no" when one fails, "—" when none was checked."""
    checked = [f for f in flags if f is not None]
    if not checked:
        return "—"
    return "yes" if all(checked) else "no"


def rate_range(rates: list[float]) -> str:
    """"1.81–2.03" for a list of rates (nan left out); "—" when there is none."""
    finite = [r for r in rates if not math.isnan(r)]
    if not finite:
        return "—"
    lo, hi = min(finite), max(finite)
    return rate_text(lo) if abs(hi - lo) < 5e-3 else f"{rate_text(lo)}–{rate_text(hi)}"


def scene_toml(path: Path, root: Path) -> dict:
    """A scene file as a dictionary (for the constants a study needs: amplitude, reference)."""
    with open(root / path, "rb") as f:
        return tomllib.load(f)


def vibration_constants(ctx: Context) -> dict:
    """Amplitude A and period T = 2 L / c, c = sqrt(E / rho0), of the vibration problem."""
    scene = scene_toml(VIBRATION, ctx.root)
    (x0, _), (x1, _) = scene["domain"]["rectangle"]
    material = scene["material"]
    c = math.sqrt(material["youngs_modulus"] / material["density"])
    return {"amplitude": scene["exact"]["amplitude"], "period": 2.0 * (x1 - x0) / c}


def at_time(rows: list[dict], t: float) -> list[dict]:
    """The rows measured at absolute time t (column `time`)."""
    return [r for r in rows if abs(number(r["time"]) - t) <= 1e-9 * max(1.0, abs(t))]


def fraction_label(fraction: float) -> str:
    """0.25 -> "T/4", 1.0 -> "T"."""
    names = {0.25: "T/4", 0.5: "T/2", 0.75: "3T/4", 1.0: "T"}
    return names.get(round(fraction, 6), f"{fraction:g} T")


def refinement_axes(axes, keys: list[str], series: dict, xlabel: str, ylabel: str) -> None:
    """Log-log axes of the errors `keys` (one per axis) of the series' rows against their
    spacing 1/n, coarse to fine, with a rate-2 guide under the lowest error; `ylabel` may
    name {key}."""
    hs = sorted({number(r["spacing"]) for rs in series.values() for r in rs}, reverse=True)
    for ax, key in zip(axes, keys):
        log_axes(ax, xlabel, ylabel.format(key=key), invert_x=True)
        level_ticks(ax, hs, reciprocal=True)
        low = min(number(r[key]) for rs in series.values() for r in rs)
        slope_guide(ax, hs[0], hs[-1], 0.5 * low * (hs[0] / hs[-1]) ** 2, 2)


def commands_block(*commands: str) -> str:
    """Shell commands as a markdown code block."""
    return "```sh\n" + "\n".join(commands) + "\n```\n"


def failed_messages(stdout: str) -> dict[tuple, str]:
    """The messages of failed runs in `mfree converge` output, by (cloud, order, scheme, h)."""
    found = {}
    pattern = re.compile(r"\[\d+/\d+\]\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+\S+\s+(\S+)\s+FAILED:\s*(.*)")
    for line in stdout.splitlines():
        m = pattern.search(line)
        if m:
            label = method_label({"scheme": m[3], "consistency": m[4]})["scheme"]
            # The message's closing advice in parentheses is left out of the tables.
            found[(m[1], m[2], label, number(m[5]))] = re.sub(r"\s*\([^()]*\)$", "", m[6].strip())
    return found


# ---------------------------------------------------------------------------------------------
# 1. Integration accuracy


def integration_expected(function: str, scheme: str, order: str, cloud: str) -> float | str:
    """Expected rate of verification/integration/README.md; "exact" or "none" where no rate."""
    if scheme == "rk":
        if order == "linear":
            return 2.0
        return 4.0 if cloud == "lattice" else 3.0
    if scheme == "voronoi":
        return 2.0
    if scheme == "equal":
        return 2.0 if cloud == "lattice" else "none"
    return 4.0 if function == "f1" else "exact"  # gauss_cells; f2 is biquadratic


def integration_check(expected, rows: list[dict]) -> tuple[str, bool]:
    """(observed rate text, whether it matches) for one series of the integration study."""
    errors = [number(r["error"]) for r in rows]
    if expected == "exact":
        return ("exact" if max(errors) < 1e-12 else rate_text(last_rate(rows, "error"))), max(errors) < 1e-12
    r = last_rate(rows, "error")
    if expected == "none":  # no convergence: the error stalls
        return rate_text(r), not (r >= 0.5)
    return rate_text(r), meets(r, expected)


def scheme_label(scheme: str, order: str) -> str:
    """"rk linear", "rk quadratic"; the baselines by name (their order column is "-")."""
    return f"{scheme} {order}" if scheme == "rk" else scheme


def integration_accuracy(ctx: Context) -> Section:
    """Measures |∫f − Σ_K w_K f(x_K)| for two smooth functions on refined lattice and random
    quadrature clouds: the RK weights (linear and quadratic) against Voronoi cells, Gauss cells
    and equal weights, and the observed rate between the two finest levels."""
    scene = INTEGRATION / ("quick.toml" if ctx.quick else "study.toml")
    run = ctx.mfree_run("integration", scene, "integration")
    rows = read_csv(run.folder / "integration.csv")
    series = group(rows, ("function", "scheme", "order", "cloud"), "points",
                   key_order=lambda k: (k[0], position(scheme_label(k[1], k[2]), INTEGRATION_SCHEMES), k[3]))

    lines, by_scheme = [], defaultdict(list)
    for (function, scheme, order, cloud), rs in series.items():
        expected = integration_expected(function, scheme, order, cloud)
        observed, ok = integration_check(expected, rs)
        finest = rs[-1]
        label = scheme_label(scheme, order)
        lines.append([function, label, cloud, int(finest["points"]), number(finest["error"]), observed,
                      expected if isinstance(expected, str) else f"{expected:g}", "yes" if ok else "no",
                      seconds_text(number(finest["seconds"]))])
        what = function if cloud == "-" else f"{function} {cloud}"
        by_scheme[label].append((what, observed, expected if isinstance(expected, str) else f"{expected:g}", ok))

    headlines = []
    for label in sorted(by_scheme, key=lambda k: position(k, INTEGRATION_SCHEMES)):
        checks = by_scheme[label]
        expectations = {c[2] for c in checks}
        expected = (expectations.pop() if len(expectations) == 1
                    else ", ".join(f"{what} {exp}" for what, _, exp, _ in checks))
        observed = ", ".join(f"{what} {obs}" for what, obs, _, _ in checks)
        headlines.append((f"Integration, {label}: rate (finest pair)", expected, observed,
                          verdict([c[3] for c in checks])))

    figure = plot_integration(ctx, series)
    negative = negative_weights_text(series)
    levels = sorted({int(r["points"]) for r in rows if r["scheme"] == "rk"})
    md = f"""**Problem.** Integrate f1 = sin(π s/2) sin(π t) (corner coordinates s = x + 1, t = y + 1/2)
and f2 = (1 − x²)(1 − 4y²) over Ω = [−1, 1] × [−1/2, 1/2] with a quadrature cloud of N points and
weights w_K, and measure |∫f − Σ w_K f(x_K)| at {len(levels)} levels ({levels[0]} to {levels[-1]} points).
Our RK weights w_K = ∫φ_K (linear and quadratic RK of the quadrature cloud) are compared with clipped
Voronoi cells, 2 × 2 Gauss points on cells of side 2h (independent of the cloud) and equal weights |Ω|/N,
on lattice and uniformly random clouds; h = sqrt(|Ω|/N).

**Expected** (verification/integration/README.md): RK linear rate 2 on every cloud; RK quadratic 3 or
better on random clouds and 4 on lattices; Voronoi 2; equal weights 2 on lattices and no convergence on
random clouds; Gauss cells 4 on f1 and f2 exact (biquadratic).

**Criterion**: the rate between the two finest levels is at least the expected one minus {TOLERANCE};
"exact" means an error below 1e-12 at every level; "none" means a rate below 0.5.

**Observed** (finest level):

{table(["function", "scheme", "cloud", "points", "error", "rate (last pair)", "expected", "match",
        "weights [s]"], lines)}
{negative}

{ctx.image(figure, "Integration error against spacing h = sqrt(|Ω|/N); solid lattice, dotted random, "
                   "dash-dotted Gauss cells (exact on f2: round-off, zero drawn at 1e-16)")}
**Reproduce**:

{commands_block(f"build/mfree integration {scene} --out results/integration",
                f"/usr/bin/python3 {INTEGRATION}/plot.py results/integration/integration.csv results/integration")}"""
    return Section("", md, headlines)


def negative_weights_text(series: dict) -> str:
    """A sentence on the negative weights of quadratic RK on random clouds, level by level."""
    parts = []
    for (function, scheme, order, cloud), rs in series.items():
        if function == "f1" and scheme == "rk" and order == "quadratic" and cloud == "random":
            parts = [f"{r['negative_weights']} at {r['points']} points (most negative {num(number(r['most_negative']), 2)})"
                     for r in rs]
    if not parts:
        return ""
    return "Negative weights of quadratic RK on random clouds: " + "; ".join(parts) + "."


def plot_integration(ctx: Context, series: dict) -> Path:
    """Error against spacing, f1 and f2 side by side; colour by scheme, line style by cloud."""
    fig, axes = new_figure(2)
    colours = {}
    for (function, scheme, order, cloud), rs in series.items():
        ax = axes[0 if function == "f1" else 1]
        label = scheme_label(scheme, order)
        colour = colours.setdefault(label, f"C{len(colours)}")
        hs = [number(r["spacing"]) for r in rs]
        es = [max(number(r["error"]), 1e-16) for r in rs]
        ax.plot(hs, es, CLOUD_STYLE.get(cloud, "-"), marker=CLOUD_MARK.get(cloud, "x"), color=colour,
                label=f"{label}, {cloud}")
    for ax, function in zip(axes, ("f1", "f2")):
        log_axes(ax, "spacing h", f"|∫{function} − Σ w f|", invert_x=True)
        ax.set_title(function)
    hs = sorted({number(r["spacing"]) for rs in series.values() for r in rs}, reverse=True)
    for order in (2, 4):
        slope_guide(axes[0], hs[0], hs[-1], 1e-2 if order == 2 else 1e-4, order)
    legend_outside(axes[1])
    return save_figure(fig, ctx.figure("integration_error_vs_spacing"))


# ---------------------------------------------------------------------------------------------
# 2. Patch tests


def patch_tests(ctx: Context) -> Section:
    """The linear patch test: an exact linear displacement prescribed on the whole boundary of
    the 2 x 1 rectangle must be reproduced to round-off by a consistent scheme, for every cloud
    and RK order; and the quadratic patch test for quadratic RK, with quadratic VCI against the
    linear symmetric correction."""
    rows, messages = [], {}
    for name, sets in (("patch_test", []), ("patch_test_gauss", GAUSS_BASELINE)):
        run = ctx.mfree_run("converge", PATCH_TEST, name, sets)
        ctx.tolerate_failed_rows(run, "patch test: a baseline scheme whose matrix cannot be factorised "
                                      "fails the test, which the table reports")
        messages |= failed_messages(run.stdout)
        rows += [method_label(r) for r in read_csv(run.folder / "convergence.csv")]
    series = group(rows, ("cloud", "order", "scheme"), "spacing", descending=True, key_order=quadrature_order)
    scene = scene_toml(PATCH_TEST, ctx.root)

    lines = []
    passed = {}  # (cloud, order, scheme) -> (largest L2 error, a run failed, passes)
    for key, rs in series.items():
        passed[key], row = patch_result(key, rs, messages)
        lines.append(list(key) + row)

    quadratic_lines, quadratic = [], {}  # scheme label -> [(largest L2 error, a run failed, passes)]
    for name, sets in (("vci", ["quadrature.consistency=vci"]), ("symmetric", ["quadrature.consistency=symmetric"]),
                       ("gauss_cells_vci", ['study.schemes=["gauss_cells"]'])):
        qrun = ctx.mfree_run("converge", PATCH_TEST, f"patch_test_quadratic_{name}", QUADRATIC_PATCH + sets)
        qmessages = failed_messages(qrun.stdout)
        for key, rs in group([method_label(r) for r in read_csv(qrun.folder / "convergence.csv")],
                             ("cloud", "order", "scheme"), "spacing", descending=True,
                             key_order=quadrature_order).items():
            result, row = patch_result(key, rs, qmessages)
            quadratic.setdefault(key[2], []).append(result)
            quadratic_lines.append([key[0], QUADRATURE_NAMES.get(key[2], key[2] + " + symmetric")] + row)

    consistent = [v for k, v in passed.items() if k[2] in CONSISTENT]
    irregular = [v for k, v in passed.items() if k[2] not in CONSISTENT and k[0] != "lattice"]
    lattice = [v for k, v in passed.items() if k[2] not in CONSISTENT and k[0] == "lattice"]
    vci = quadratic.get("projected_vci", []) + quadratic.get("gauss_cells_vci", [])
    symmetric = quadratic.get("projected", [])
    headlines = [
        ("Patch test, Gauss cells + VCI and projected + symmetric correction, every cloud, linear and quadratic RK",
         f"L2 error < {PATCH_TOLERANCE:.0e}", largest_text(consistent), verdict([v[2] for v in consistent])),
        ("Patch test, Gauss cells and nodal integration on perturbed and random clouds",
         "do not pass", patch_summary(irregular), verdict([not v[2] for v in irregular])),
        ("Patch test, Gauss cells and nodal integration on the lattice", "— (not stated)",
         patch_summary(lattice), "—"),
        ("Quadratic patch test, quadratic RK, quadratic VCI on projected gradients and Gauss cells, every cloud",
         f"L2 error < {PATCH_TOLERANCE:.0e}", largest_text(vci), verdict([v[2] for v in vci] or [False])),
        ("Quadratic patch test, quadratic RK, projected + linear symmetric correction",
         "does not pass (linear consistency only)", patch_summary(symmetric),
         verdict([not v[2] for v in symmetric] or [False])),
    ]
    spacings = ", ".join(f"{h:g}" for h in scene["study"]["spacings"])
    exact = scene["exact"]
    hessians = dict(item.split("=", 1) for item in QUADRATIC_PATCH if item.startswith("exact.hessian"))
    columns = ["L2 displacement", "energy", "consistency defect", "passes"]
    md = f"""**Problem.** The 2 × 1 rectangle [−1, 1] × [−1/2, 1/2], {scene["material"]["model"].replace("_", " ")},
carries the exact linear displacement u = a + G x with a = {exact["offset"]} and G = {exact["gradient"]}
(constant strain, no body force), prescribed on all four sides by Nitsche's method. Linear and quadratic RK
reproduce linear fields, so any error is the quadrature's. Node spacings {spacings}; lattice, perturbed
(±{scene["nodes"]["perturbation"] / 2:g} h) and random clouds; the default scheme (3 × 3 Gauss points per cell with VCI) and the
projected scheme with the symmetric consistency correction, against Gauss cells without a correction (4 × 4
points, 6 × 6 for quadratic RK) and direct nodal integration. Scene: `{PATCH_TEST}`.

The quadratic patch test adds u_c += x^T H_c x / 2 with H_x = {hessians["exact.hessian_x"]} and
H_y = {hessians["exact.hessian_y"]}: linear stress and the constant body force −div σ, for quadratic RK,
whose functions contain the field, with quadratic VCI (`consistency = "vci"`, of the RK order: the moment
conditions of 1, x and y at the row centroids, include/mfree/galerkin/consistency.hpp) on the projected
scheme and on Gauss cells, and on the projected scheme with its default linear symmetric correction.

**Expected**: a scheme that is integration-consistent passes the linear patch test to round-off. The
projected scheme with the consistency correction and Gauss cells with VCI restore it (verification/cantilever/README.md),
so they pass on every cloud for linear and quadratic RK; uncorrected Gauss cells misintegrate the rational RK
functions and direct nodal integration is not consistent, so neither is expected to pass on irregular clouds.
Quadratic VCI meets the conditions of the quadratic patch test and passes it on every cloud; the symmetric
correction meets the linear ones only and does not.

**Criterion**: largest relative L2 displacement error over the spacings below {PATCH_TOLERANCE:.0e}
(and no failed run).

**Observed** (largest over the spacings; the consistency defect is the largest residual of the
integration-consistency conditions of the RK order after the correction, for Gauss cells and nodal
integration the uncorrected one; for quadratic RK these include the moments of x and y, which the
symmetric correction leaves):

{table(["cloud", "RK", "quadrature"] + columns, lines)}
Quadratic patch test, quadratic RK:

{table(["cloud", "quadrature"] + columns, quadratic_lines)}
**Reproduce**:

{commands_block(ctx.command("converge", PATCH_TEST), ctx.command("converge", PATCH_TEST, GAUSS_BASELINE),
                ctx.command("converge", PATCH_TEST, QUADRATIC_PATCH + ["quadrature.consistency=vci"]),
                ctx.command("converge", PATCH_TEST, QUADRATIC_PATCH + ['study.schemes=["gauss_cells"]']))}"""
    return Section("", md, headlines)


def patch_result(key: tuple, rs: list[dict], messages: dict) -> tuple[tuple[float, bool, bool], list]:
    """(largest L2 error, a run failed, passes) of one patch-test series, and its table cells
    (L2, energy, consistency defect, passes)."""
    failures = [f"h = {r['spacing']}: {messages.get(key + (number(r['spacing']),), 'failed')}"
                for r in rs if not r["dofs"].strip()]
    good = [r for r in rs if r["dofs"].strip()]
    worst = max((number(r["l2_displacement"]) for r in good), default=math.nan)
    energy = max((number(r["energy"]) for r in good), default=math.nan)
    defect = max((number(r["consistency_after"]) for r in good), default=math.nan)
    passes = not failures and worst < PATCH_TOLERANCE
    shown = "yes" if passes else ("no (" + "; ".join(failures) + ")" if failures else "no")
    return (worst, bool(failures), passes), [worst, energy, defect, shown]


def largest_text(results: list[tuple[float, bool, bool]]) -> str:
    """"largest 2.9e-13" (and the failed runs) of a set of patch tests."""
    if not results:
        return "no result"
    failed = sum(v[1] for v in results)
    return f"largest {num(max(v[0] for v in results))}" + (f", {failed} run(s) failed" if failed else "")


def patch_summary(results: list[tuple[float, bool, bool]]) -> str:
    """"L2 errors 7.5e-07 … 1.6e-02, 1 run failed, none passes" for a set of patch tests."""
    errors = [v[0] for v in results if not math.isnan(v[0])]
    text = f"L2 errors {num(min(errors))} … {num(max(errors))}" if errors else "no result"
    failed = sum(v[1] for v in results)
    if failed:
        text += f", {failed} run(s) failed"
    passes = sum(v[2] for v in results)
    return text + (f", {passes} pass" if passes else ", none passes")


# ---------------------------------------------------------------------------------------------
# 3. Cantilever, small deformation

NORMS = [("l2_displacement", "L2 displacement"), ("energy", "energy"), ("l2_stress", "L2 stress")]
ORDER = {"linear": 1, "quadratic": 2}


def cantilever_expected(cloud: str, order: str, scheme: str) -> dict | str:
    """Expected rates (L2 displacement, energy, L2 stress) of verification/cantilever/README.md;
    for the baselines on perturbed clouds, "loses convergence"."""
    p = ORDER[order]
    if scheme.startswith("projected"):
        return {"l2_displacement": p + 1.0, "energy": float(p), "l2_stress": float(p)}
    if scheme == "gauss_cells_vci":  # quadratic RK: 4 x 4 points and VCI on the monomials up to degree 2
        return {"l2_displacement": p + 1.0, "energy": float(p), "l2_stress": float(p)}
    if cloud != "lattice":
        return "loses convergence"
    return "—"


def cantilever_small(ctx: Context) -> Section:
    """The Timoshenko cantilever refined on lattice and perturbed clouds, linear and quadratic RK,
    three quadratures: relative L2 displacement, energy and L2 stress errors and their rates, and
    the tip deflection against the exact one."""
    sets = CANTILEVER_QUICK if ctx.quick else []
    run = ctx.mfree_run("converge", CANTILEVER, "cantilever", sets)
    vci = ctx.mfree_run("converge", CANTILEVER, "cantilever_vci", sets + QUADRATIC_VCI)
    gauss = ctx.mfree_run("converge", CANTILEVER, "cantilever_gauss", sets + GAUSS_BASELINE)
    rows = [method_label(r) for one in (run, vci, gauss) for r in read_csv(one.folder / "convergence.csv")]
    # The work-precision section also takes the finer perturbed runs; this section's tables and
    # rates keep the common levels.
    fine = [] if ctx.quick else [
        ctx.mfree_run("converge", CANTILEVER, name, PERTURBED_FINE + extra)
        for name, extra in (("cantilever_fine_vci", []), ("cantilever_fine_gauss", GAUSS_BASELINE[1:]))]
    ctx.data["cantilever"] = rows + [method_label(r) for one in fine for r in read_csv(one.folder / "convergence.csv")]
    # The comparison with deal.II's Q2 (work-precision section) is at one thread, as its figures
    # are: the consistent schemes on the lattice once more, with OMP_NUM_THREADS = 1.
    lattice = ['study.clouds=["lattice"]'] + (sets or ["study.spacings=[1.5, 0.75, 0.375]"])
    one_thread = [ctx.mfree_run("converge", CANTILEVER, name, lattice + extra, threads=1)
                  for name, extra in (("cantilever_one_thread", ['study.schemes=["projected", "gauss_cells"]']),
                                      ("cantilever_one_thread_vci", QUADRATIC_VCI))]
    ctx.data["cantilever_one_thread"] = [method_label(r) for one in one_thread
                                         for r in read_csv(one.folder / "convergence.csv")]
    reference = scene_toml(CANTILEVER, ctx.root)["study"]["reference"]
    series = group([r for r in rows if r["dofs"].strip()], ("cloud", "order", "scheme"), "spacing", descending=True,
                   key_order=quadrature_order)
    failed = [r for r in rows if not r["dofs"].strip()]
    failed_keys = {(r["cloud"], r["order"], r["scheme"]) for r in failed}

    results, checks = [], []
    for (cloud, order, scheme), rs in series.items():
        finest = rs[-1]
        rates = {key: last_rate(rs, key) for key, _ in NORMS}
        tip = number(finest["probe_uy"])
        results.append([cloud, order, scheme, finest["spacing"], int(finest["dofs"]),
                        number(finest["l2_displacement"]), rate_text(rates["l2_displacement"]),
                        number(finest["energy"]), rate_text(rates["energy"]),
                        number(finest["l2_stress"]), rate_text(rates["l2_stress"]),
                        f"{tip:.7f}", f"{100 * (tip - reference) / reference:+.2f} %",
                        seconds_text(number(finest["seconds"]))])
        checks.append(((cloud, order, scheme), cantilever_expected(cloud, order, scheme), rates,
                       (cloud, order, scheme) in failed_keys))
    for key in sorted(failed_keys - set(series), key=quadrature_order):  # every level failed
        checks.append((key, cantilever_expected(*key), {k: math.nan for k, _ in NORMS}, True))

    check_lines, headlines = cantilever_checks(checks)
    headlines.append(cantilever_tip_headline(series, reference))
    failed_text = ("Runs that failed: " + ", ".join(f"{r['cloud']} {r['order']} {r['scheme']} h = {r['spacing']}"
                                                   for r in failed) + ".\n") if failed else ""
    figure = plot_cantilever(ctx, series)
    spacings = sorted({number(r["spacing"]) for r in rows}, reverse=True)
    md = f"""**Problem.** The plane-stress Timoshenko beam [0, 48] × [−6, 6] (E = 3e7, ν = 0.3) under the
parabolic end shear P = 1000, exact displacements on x = 0 by Nitsche's method; node spacings
{", ".join(f"{h:g}" for h in spacings)} on lattice and perturbed (±0.15 h) clouds, linear and quadratic RK,
with the default scheme, 3 × 3 (linear RK) or 4 × 4 (quadratic) Gauss points per cell with VCI of the RK
order (`gauss_cells_vci`: test gradients meeting the moment conditions of 1 (linear RK) or 1, x, y, x², xy
and y² (quadratic), trial gradients
untouched; a non-symmetric matrix), our projected quadrature (symmetric consistency correction), quadratic
RK on the projected quadrature with quadratic VCI (`projected_vci`), and two baselines without a
correction: Gauss cells (4 × 4 points per cell for linear RK, 6 × 6 for quadratic) and direct nodal
integration.
Errors are relative norms measured with an independent 4 × 4 Gauss rule on cells of h/2. Tip deflection
u_y(48, 0) against the exact {reference}.

**Expected** (verification/cantilever/README.md): linear RK, L2 displacement rate 2, energy and stress rate 1
(lattices superconverge to about 1.5); quadratic RK 3 and 2. Direct nodal integration loses convergence on
irregular clouds; Gauss cells misintegrate the rational RK functions there and stall. The README also notes
that quadratic RK with the symmetric correction reaches L2 rate 3 but energy rate about 1.3–1.5: it enforces
linear consistency only, and by changing the trial gradients too it loses their quadratic reproduction.
Quadratic VCI keeps the trial gradients and meets the quadratic conditions: energy and stress rate 2
expected; its L2 rate is held to the same 3 on the projected scheme. Gauss cells with VCI: energy and
stress rate p; L2 rate 2 for linear RK, none asserted for quadratic RK (3 × 3 points integrate the
trial side's rational functions inexactly: its L2 error is erratic below 1e-4).

**Criterion**: consistent schemes, each rate between the two finest levels at least the expected one minus
{TOLERANCE}; baselines on perturbed clouds, "loses convergence" holds when the energy rate is below p − {TOLERANCE}
(p the RK order) or a run fails.

**Observed** (finest level, rates between the two finest levels):

{table(["cloud", "RK", "quadrature", "h", "DOFs", "L2 disp", "rate", "energy", "rate", "L2 stress", "rate",
        "tip u_y", "tip vs exact", "solve [s]"], results)}
{failed_text}
**Verdicts** (rates between the two finest levels):

{table(["cloud", "RK", "quadrature", "expected (L2, energy, stress)", "observed", "match"], check_lines)}
{ctx.image(figure, "Cantilever: relative errors against node spacing; solid lattice, dashed perturbed")}
**Reproduce**:

{commands_block(ctx.command("converge", CANTILEVER, sets), ctx.command("converge", CANTILEVER, sets + QUADRATIC_VCI),
                ctx.command("converge", CANTILEVER, sets + GAUSS_BASELINE))}"""
    return Section("", md, headlines)


def cantilever_checks(checks: list) -> tuple[list[list], list[tuple]]:
    """Verdict rows per (cloud, order, scheme) and the summary headlines of the cantilever; a
    series with a failed run fails the expected rates and shows the expected loss of convergence."""
    lines, by_group = [], defaultdict(list)
    for (cloud, order, scheme), expected, rates, failed in checks:
        observed = ", ".join(rate_text(rates[k]) for k, _ in NORMS) + (" (a run failed)" if failed else "")
        if isinstance(expected, dict):
            ok = not failed and all(meets(rates[k], expected[k]) for k in expected)
            shown = ", ".join(f"{expected[k]:g}" if k in expected else "—" for k, _ in NORMS)
            by_group[f"{QUADRATURE_NAMES.get(scheme, scheme)}, {order} RK"].append((cloud, observed, shown, ok))
        elif expected == "loses convergence":
            ok = failed or not (rates["energy"] >= ORDER[order] - TOLERANCE)
            shown = f"loses convergence (energy rate < {ORDER[order] - TOLERANCE:g})"
            by_group["Gauss cells and nodal on perturbed clouds"].append(
                (f"{scheme} {order}", observed, "loses convergence (energy rate < p − 0.3, p the RK order)", ok))
        else:
            ok, shown = None, "—"
        lines.append([cloud, order, scheme, shown, observed, "—" if ok is None else ("yes" if ok else "no")])
    headlines = []
    for what, group_checks in by_group.items():
        expected = "; ".join(sorted({c[2] for c in group_checks}))
        observed = "; ".join(f"{c[0]} {c[1]}" for c in group_checks)
        headlines.append((f"Cantilever, {what}: rates (L2, energy, stress)", expected, observed,
                          verdict([c[3] for c in group_checks])))
    return lines, headlines


def cantilever_tip_headline(series: dict, reference: float) -> tuple:
    """The tip deflection of the projected scheme at the finest level. The README's figure is
    for h = 0.375; coarser studies (quick mode) are reported without a verdict."""
    deviations = [(k, (number(rs[-1]["probe_uy"]) - reference) / reference, number(rs[-1]["spacing"]))
                  for k, rs in series.items() if k[2] == "projected"]
    if not deviations:
        return ("Cantilever tip deflection, projected", "within 0.1 % at h = 0.375", "no result", "no")
    worst = max(deviations, key=lambda d: abs(d[1]))
    h = worst[2]
    observed = f"largest deviation {100 * worst[1]:+.3f} % ({worst[0][0]}, {worst[0][1]}) at h = {h:g}"
    return ("Cantilever tip deflection u_y(48, 0), projected, finest level", "within 0.1 % at h = 0.375 (README: 0.08 %)",
            observed, ("yes" if abs(worst[1]) < 1e-3 else "no") if h <= 0.375 + 1e-12 else "—")


def plot_cantilever(ctx: Context, series: dict) -> Path:
    """The three error norms against spacing; colour by quadrature and order, line style by cloud."""
    fig, axes = new_figure(3, width=5.5)
    colours = {}
    for (cloud, order, scheme), rs in series.items():
        colour = colours.setdefault((scheme, order), f"C{len(colours)}")
        hs = [number(r["spacing"]) for r in rs]
        for ax, (key, _) in zip(axes, NORMS):
            ax.plot(hs, [number(r[key]) for r in rs], CLOUD_STYLE[cloud], marker=CLOUD_MARK[cloud], color=colour,
                    label=f"{scheme}, {order}, {cloud}")
    hs = [number(r["spacing"]) for rs in series.values() for r in rs]
    for ax, (_, name) in zip(axes, NORMS):
        log_axes(ax, "node spacing h", f"relative {name} error", invert_x=True)
        level_ticks(ax, hs)
    legend_outside(axes[-1])
    return save_figure(fig, ctx.figure("cantilever_error_vs_spacing"))


# ---------------------------------------------------------------------------------------------
# 4. Cantilever, large deformation

LARGE_FULL_DEFLECTION = 20.5  # verification/cantilever/README.md: |u_y| at the full load
LARGE_FULL_SHORTENING = 5.1  # and the tip's motion back


def cantilever_large(ctx: Context) -> Section:
    """The cantilever as a Neo-Hookean solid under 25 load steps to a tip deflection of about 43 % of
    its length: Newton iterations per step, the load-deflection curve, and the difference from the
    small-strain solution, which must vanish at small loads."""
    run = ctx.mfree_run("run", LARGE_DEFORMATION, "cantilever_large")
    rows = read_csv(run.folder / "load_steps.csv")
    length = 48.0

    lines = []
    for r in rows:
        uy, linear = number(r["probe_uy"]), number(r["linear_probe_uy"])
        lines.append([r["load_factor"], int(r["iterations"]), int(r["cutbacks"]), number(r["probe_ux"]), number(uy),
                      number(linear), f"{uy / linear:.4f}", number(r["l2_displacement_vs_linear"])])
    first, last = rows[0], rows[-1]
    small_difference = number(first["l2_displacement_vs_linear"])
    deflection, shortening = abs(number(last["probe_uy"])), abs(number(last["probe_ux"]))
    iterations = [int(r["iterations"]) for r in rows]
    cutbacks = sum(int(r["cutbacks"]) for r in rows)
    headlines = [
        ("Large deformation: difference from small strain at the smallest load",
         "L2 difference < 1e-2 (README: 2.9e-3, the linear problem's discretisation error)",
         f"{num(small_difference)} at load factor {first['load_factor']}", "yes" if small_difference < 1e-2 else "no"),
        ("Large deformation: tip deflection at the full load",
         f"{LARGE_FULL_DEFLECTION} (README), within 2 %; shortening {LARGE_FULL_SHORTENING}",
         f"{deflection:.2f} ({100 * deflection / length:.0f} % of L), shortening {shortening:.2f}; small strain "
         f"{abs(number(last['linear_probe_uy'])):.1f}",
         "yes" if abs(deflection - LARGE_FULL_DEFLECTION) <= 0.02 * LARGE_FULL_DEFLECTION else "no"),
        ("Large deformation: Newton", "every step converges, no cut-back, ≤ 5 iterations per step (README: 85 in all)",
         f"{sum(iterations)} iterations, {min(iterations)}–{max(iterations)} per step, {cutbacks} cut-back(s)",
         "yes" if cutbacks == 0 and max(iterations) <= 5 else "no"),
    ]
    figure = plot_load_deflection(ctx, rows)
    md = f"""**Problem.** The beam of the small-deformation study as a compressible Neo-Hookean solid (plane strain, E = 3e7,
ν = 0.3), total-Lagrangian, solved by Newton with {len(rows)} load steps: the Timoshenko end shear
P = 3e6 (a dead load) and the Timoshenko clamp displacements, both scaled by the load factor; h = 0.75.
At small loads the solution must be Timoshenko's (plane-strain constants); at the full load the beam
deflects by about 43 % of its length.

**Expected** (verification/cantilever/README.md): tip (48, 0) deflection 20.5 and motion back 5.1 at the
full load, where small-strain theory predicts 24.4 and no shortening; at load factors 1e-4 and 1e-3 the
relative L2 difference from the Timoshenko field is 2.9e-3 (the linear problem's discretisation error),
growing with the load; Newton needs 2 iterations at small loads and 3–4 at large ones (85 in all), no
cut-back, to |R| / |R_0| < 1e-10.

**Criterion**: L2 difference below 1e-2 at the smallest load; full-load deflection within 2 % of 20.5;
no cut-back and at most 5 iterations per step.

**Observed** (probe at the tip (48, 0); "small strain" is the linear solution at the same load factor):

{table(["load factor", "Newton iterations", "cut-backs", "u_x", "u_y", "small-strain u_y", "u_y / small strain",
        "L2 difference from small strain"], lines)}
{ctx.image(figure, "Large-deformation cantilever: tip displacement against the load factor")}
**Reproduce** (also writes a `.pvd` series of the load steps for ParaView):

{commands_block(ctx.command("run", LARGE_DEFORMATION))}"""
    return Section("", md, headlines)


def plot_load_deflection(ctx: Context, rows: list[dict]) -> Path:
    """Tip deflection and shortening against the load factor, with the small-strain deflection."""
    fig, axes = new_figure(1, width=7.0)
    ax = axes[0]
    load = [0.0] + [number(r["load_factor"]) for r in rows]
    ax.plot(load, [0.0] + [abs(number(r["probe_uy"])) for r in rows], "o-", label="|u_y| tip, Neo-Hookean")
    ax.plot(load, [0.0] + [abs(number(r["probe_ux"])) for r in rows], "s-", label="|u_x| tip (shortening)")
    ax.plot(load, [0.0] + [abs(number(r["linear_probe_uy"])) for r in rows], "k--", label="|u_y| tip, small strain")
    ax.set_xlabel("load factor")
    ax.set_ylabel("tip displacement")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return save_figure(fig, ctx.figure("cantilever_load_deflection"))


# ---------------------------------------------------------------------------------------------
# 5. Meshfree vibration

MOTION = [("displacement", "u"), ("velocity", "v"), ("stress", "stress")]


def meshfree_vibration(ctx: Context) -> Section:
    """The Neo-Hookean vibration problem with the total-Lagrangian meshfree method, explicit and
    implicit: RMS errors of displacement, velocity and stress at each error time, refined in h, and
    their rates."""
    sets = VIBRATION_QUICK if ctx.quick else VIBRATION_FULL
    run = ctx.mfree_run("converge", VIBRATION, "vibration", sets)
    rows = read_csv(run.folder / "convergence.csv")
    ctx.data["vibration"] = rows
    constants = vibration_constants(ctx)
    period = constants["period"]
    series = group(rows, ("time_scheme", "time"), "spacing", descending=True,
                   key_order=lambda k: (k[0], number(k[1])))

    main, rate_lines, by_scheme = [], [], defaultdict(lambda: defaultdict(list))
    for (scheme, t), rs in series.items():
        fraction = number(t) / period
        rates = {key: series_rates(rs, key) for key, _ in MOTION}
        if abs(fraction - 0.25) < 1e-6:
            for i, r in enumerate(rs):
                main.append([scheme, f"1/{1 / number(r['spacing']):g}", int(r["dofs"]), number(r["time_step"])]
                            + sum(([number(r[key]), rate_text(rates[key][i - 1]) if i else "—"] for key, _ in MOTION), [])
                            + [seconds_text(number(r["seconds"]))])
        last = {key: (rates[key][-1] if rates[key] else math.nan) for key, _ in MOTION}
        for key, _ in MOTION:
            by_scheme[scheme][key].append(last[key])
        rate_lines.append([scheme, fraction_label(fraction)] + [rate_text(last[k]) for k, _ in MOTION]
                          + [verdict([meets(last[k], 2.0) for k, _ in MOTION])])

    headlines = []
    for scheme, rates in by_scheme.items():
        headlines.append((f"Meshfree vibration, {scheme}: displacement rate at every error time (finest pair)",
                          "2 (≥ 1.7)", rate_range(rates["displacement"]),
                          verdict([meets(r, 2.0) for r in rates["displacement"]])))
        headlines.append((f"Meshfree vibration, {scheme}: velocity and stress rates (finest pair)", "2 (≥ 1.7)",
                          f"v {rate_range(rates['velocity'])}, stress {rate_range(rates['stress'])}",
                          verdict([meets(r, 2.0) for r in rates["velocity"] + rates["stress"]])))
    checks = list(dict.fromkeys(re.findall(r"time-step check.*", run.stdout)))  # printed twice by mfree
    check_text = ("**Time-step check** (the finest level again with dt / 2):\n\n"
                  + "".join(f"- {c}\n" for c in checks)) if checks else ""
    quick_note = ("In quick mode the run ends at T/4 = 0.005 s (the period is 0.02 s), the only error time, and "
                  "the time-step check is off.\n" if ctx.quick else
                  "The time-step check (the finest level again with dt / 2) is left to `bash verification/vibration/run.sh` "
                  "to keep the report within 30 minutes; verification/vibration/README.md gives its result (the "
                  "errors change by at most 0.13 % explicit, 1.14 % Newmark: space dominates).\n")
    spacings = sorted({number(r["spacing"]) for r in rows}, reverse=True)
    figure = plot_vibration(ctx, series, period)
    md = f"""**Problem.** The unit square of compressible Neo-Hookean material (E = 1e7 Pa, ν = 0.3,
ρ0 = 1000 kg/m³, plane strain) in the manufactured motion u_x = A sin(2πX) sin(cπt),
u_y = A sin(2πY) sin(cπt + π), A = {constants["amplitude"]}, c = 100 m/s, period T = {period:g} s,
driven by its body force, with slip walls. Linear RK on lattices of spacing
{", ".join(f"1/{1 / h:g}" for h in spacings)}, our projected quadrature, total-Lagrangian forces;
explicit central differences (lumped mass) and Newmark average acceleration (consistent mass). Errors
are RMS over the body, integrated by independent Gauss cells. {quick_note}

**Expected** (verification/vibration/README.md): rate 2 in h for displacement, velocity and stress
(observed there between 1.80 and 2.20 at the finest pair, h = 1/32 to 1/64).

**Criterion**: every rate between the two finest levels at least {2 - TOLERANCE:g}.

**Observed at T/4** (displacement and stress peak; RMS errors, rates between consecutive levels,
run time reported by mfree, error measurement excluded):

{table(["scheme", "h", "DOFs", "dt", "u", "rate", "v", "rate", "stress", "rate", "wall [s]"], main)}
**Rates between the two finest levels at every error time**:

{table(["scheme", "t", "u", "v", "stress", "match"], rate_lines)}
{check_text}
{ctx.image(figure, "Meshfree vibration: RMS errors against node spacing at each error time")}
**Reproduce**:

{commands_block(ctx.command("converge", VIBRATION, sets))}"""
    return Section("", md, headlines)


def plot_vibration(ctx: Context, series: dict, period: float) -> Path:
    """Displacement, velocity and stress errors against spacing; colour by time scheme, marker by
    error time."""
    fig, axes = new_figure(3, width=5.5)
    colours, markers = {}, {}
    for (scheme, t), rs in series.items():
        colour = colours.setdefault(scheme, f"C{len(colours)}")
        fraction = number(t) / period
        marker = markers.setdefault(round(fraction, 6), "osd^v<>"[len(markers) % 7])
        hs = [number(r["spacing"]) for r in rs]
        for ax, (key, _) in zip(axes, MOTION):
            ax.plot(hs, [number(r[key]) for r in rs], "-", marker=marker, color=colour,
                    label=f"{scheme}, {fraction_label(fraction)}")
    refinement_axes(axes, [key for key, _ in MOTION], series, "node spacing h", "RMS {key} error")
    legend_outside(axes[-1])
    return save_figure(fig, ctx.figure("vibration_error_vs_spacing"))


# ---------------------------------------------------------------------------------------------
# 6. MPM vibration

# Expected displacement rates at T/4 by method (verification/mpm-vibration/README.md, seed 000):
# (what is expected, [(coarse cells, fine cells, test on the rate, criterion text)]).
MPM_EXPECTED = {
    "classic": ("does not converge (cell-crossing error)", [(None, None, lambda r: r < 0.5, "rate < 0.5, finest pair")]),
    "ugimp": ("about 1 up to 32 cells, stalls at 64", [(16, 32, lambda r: r >= 1 - TOLERANCE, "≥ 0.7, 16→32")]),
    "cpdi": ("2–3 up to 32 cells (its 64-cell error is at the time-step floor)",
             [(16, 32, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 16→32")]),
    # cpGIMP is finite GIMP on this diagonal-F motion; qCPDI follows the exact averages over the
    # parallelogram; CPDI2 follows lCPDI (verification/mpm-vibration/README.md).
    "cpgimp": ("2–3 up to 32 cells, as lCPDI", [(16, 32, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 16→32")]),
    "qcpdi": ("2–3 up to 32 cells, as lCPDI", [(16, 32, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 16→32")]),
    "cpdi2": ("2–3 up to 32 cells, as lCPDI", [(16, 32, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 16→32")]),
    "bspline": ("about 2 up to 32 cells, stalls at 64",
                [(16, 32, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 16→32"), (32, 64, lambda r: r < 1.0, "< 1, 32→64")]),
    "bspline_cubic": ("keeps converging to 64 cells with 9 particles per cell",
                      [(32, 64, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 32→64")]),
    # The B-splines averaged over cpGIMP's domains integrate the internal force exactly over
    # domains that tile the body: no quadrature stall (verification/mpm-vibration/README.md).
    "bspline_cpgimp": ("keeps converging to 64 cells", [(32, 64, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 32→64")]),
    "bspline_cpgimp_cubic": ("keeps converging to 64 cells", [(32, 64, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 32→64")]),
    "bspline_mls": ("keeps converging where B-splines stall", [(32, 64, lambda r: r >= 2 - TOLERANCE, "≥ 1.7, 32→64")]),
}


def mpm_pair_rate(rows: list[dict], coarse: int | None, fine: int | None, key: str = "displacement") -> float | None:
    """The rate between two grids (cells), or between the two finest when both are None; None when
    the study did not run them."""
    by_cells = {int(r["cells"]): r for r in rows}
    if coarse is None:
        if len(rows) < 2:
            return None
        a, b = rows[-2], rows[-1]
    elif coarse in by_cells and fine in by_cells:
        a, b = by_cells[coarse], by_cells[fine]
    else:
        return None
    return rate(number(a[key]), number(b[key]), number(a["spacing"]), number(b["spacing"]))


def mpm_vibration(ctx: Context) -> Section:
    """The vibration problem with every MPM method (Classic, uGIMP, cpGIMP, lCPDI, qCPDI, CPDI2,
    quadratic and cubic B-splines, MLS-reconstructed B-splines): RMS errors over the particles at
    T/4 refined in the grid, and the rates each method is known for."""
    sets = MPM_QUICK if ctx.quick else MPM_FULL
    run = ctx.mfree_run("converge", MPM_VIBRATION, "mpm_vibration", sets)
    rows = read_csv(run.folder / "mpm_convergence.csv")
    ok = [r for r in rows if r["status"] == "ok"]
    failed = [r for r in rows if r["status"] != "ok"]
    ctx.data["mpm"] = ok
    period = vibration_constants(ctx)["period"]
    quarter = group(at_time(ok, period / 4), ("method", "particles_per_cell"), "cells",
                    key_order=lambda k: (position(k[0], MPM_METHODS), k[0], int(k[1])))

    main, checks, headlines = [], [], []
    for (method, ppc), rs in quarter.items():
        rates = {key: series_rates(rs, key) for key in ("displacement", "grid_velocity", "stress")}
        for i, r in enumerate(rs):
            def rate_at(key):
                return rate_text(rates[key][i - 1]) if i else "—"
            main.append([method, int(ppc), int(r["cells"]), number(r["displacement"]), rate_at("displacement"),
                         number(r["velocity"]), number(r["grid_velocity"]), rate_at("grid_velocity"),
                         number(r["stress"]), rate_at("stress"), number(r["reconstruction_defect"]),
                         seconds_text(number(r["seconds"]))])
        expected, tests = MPM_EXPECTED.get(method, ("—", []))
        flags, observed = [], []
        for coarse, fine, test, criterion in tests:
            r = mpm_pair_rate(rs, coarse, fine)
            pair = f"{coarse}→{fine}" if coarse else "finest pair"
            if r is None:
                observed.append(f"{pair}: not run")
                flags.append(None)
            else:
                observed.append(f"{pair}: {rate_text(r)}")
                flags.append(bool(test(r)))
        all_rates = ", ".join(f"{a['cells']}→{b['cells']} {rate_text(x)}"
                              for a, b, x in zip(rs, rs[1:], rates["displacement"]))
        criterion = "; ".join(t[3] for t in tests)
        checks.append([method, int(ppc), expected, criterion, all_rates, verdict(flags)])
        headlines.append((f"MPM vibration, {method}, {ppc} particles per cell: u rate at T/4", expected,
                          "; ".join(observed), verdict(flags)))

    failed_text = ("**Failed runs**: " + "; ".join(f"{r['method']} {r['cells']} cells: {r['status']}" for r in failed)
                   + "\n") if failed else ""
    times_table = mpm_rates_by_time(ok, period)
    figure = plot_mpm(ctx, quarter)
    cells = sorted({int(r["cells"]) for r in rows})
    ppcs = sorted({int(r["particles_per_cell"]) for r in rows})
    quick_note = ("In quick mode the grids are 8 and 16 cells with 4 particles per cell and the runs end at T/4, "
                  "so the criteria on finer grids are not checked (—); the README reports cubic B-splines with 4 "
                  "particles per cell diverging.\n" if ctx.quick else "")
    md = f"""**Problem.** The vibration problem of the meshfree study (A = 0.05) with the Material Point Method:
particles on a regular sub-lattice ({", ".join(map(str, ppcs))} per cell), grids of
{", ".join(map(str, cells))} cells, USF, dt = 1e-5 s, slip walls. Methods: Classic (hats), uGIMP, cpGIMP
(the domain stretched along the axes), CPDI (lCPDI), qCPDI (the parallelogram as an 8-node serendipity
element), CPDI2 (tracked corners), quadratic and cubic B-splines, and quadratic B-splines with MLS
reconstruction (seed 000). Errors
are RMS over the particles of x_p − X_p, the particle velocity v_p, the grid velocity at the particles
v_grid and the Cauchy stress, each against the exact value at X_p. {quick_note}

**Expected** (verification/mpm-vibration/README.md, seed 000): Classic MPM does not converge; uGIMP about 1
up to 32 cells; CPDI 2–3 up to 32 cells, and cpGIMP, qCPDI and CPDI2 with it; quadratic B-splines about 2 up to 32 cells and stall at 64; cubic
B-splines keep converging with 9 particles per cell; MLS keeps converging where B-splines stall (less
accurate on coarse grids, and it does not conserve mass).

**Criterion** (displacement at T/4, per method; expected rate minus {TOLERANCE} where a rate is expected):

{table(["method", "ppc", "expected", "criterion", "observed rates", "match"], checks)}
**Observed at T/4** (rates between consecutive grids; mass defect: the MLS reconstruction's mass
against the particles', before the solver scales the densities to remove it (the grid mass then
equals the particles' to round-off; 0 for the other methods); wall time of the whole run):

{table(["method", "ppc", "cells", "u", "rate", "v_p", "v_grid", "rate", "stress", "rate", "mass defect", "wall [s]"],
       main)}
{times_table}
{failed_text}
{ctx.image(figure, "MPM vibration: RMS errors over the particles at T/4 against cell size")}
**Reproduce**:

{commands_block(ctx.command("converge", MPM_VIBRATION, sets))}"""
    return Section("", md, headlines)


def mpm_rates_by_time(rows: list[dict], period: float) -> str:
    """Displacement rates between consecutive grids at every error time (when there are several)."""
    times = sorted({number(r["time"]) for r in rows})
    if len(times) < 2:
        return ""
    lines = []
    series = group(rows, ("method", "particles_per_cell", "time"), "cells",
                   key_order=lambda k: (position(k[0], MPM_METHODS), k[0], int(k[1]), number(k[2])))
    for (method, ppc, t), rs in series.items():
        rates = series_rates(rs, "displacement")
        lines.append([method, int(ppc), fraction_label(number(t) / period)]
                     + [f"{a['cells']}→{b['cells']}: {rate_text(x)}" for a, b, x in zip(rs, rs[1:], rates)])
    width = max(len(line) for line in lines)
    lines = [line + [""] * (width - len(line)) for line in lines]
    return ("**Displacement rates at every error time**:\n\n"
            + table(["method", "ppc", "t"] + ["rate"] * (width - 3), lines))


def plot_mpm(ctx: Context, quarter: dict) -> Path:
    """Displacement and stress errors at T/4 against cell size, one line per method."""
    fig, axes = new_figure(2)
    for (method, ppc), rs in quarter.items():
        hs = [number(r["spacing"]) for r in rs]
        for ax, key in zip(axes, ("displacement", "stress")):
            ax.plot(hs, [number(r[key]) for r in rs], "o-", color=f"C{position(method, MPM_METHODS)}",
                    label=f"{method}, {ppc} ppc")
    refinement_axes(axes, ["displacement", "stress"], quarter, "cell size h", "RMS {key} error at T/4")
    legend_outside(axes[-1])
    return save_figure(fig, ctx.figure("mpm_error_vs_cell_size"))


# ---------------------------------------------------------------------------------------------
# 6b. MPM options: Verlet, the pseudo-inverse mapping, MLS with the quadratic basis

MPM_MAPPING = Path("verification/mpm-vibration/mapping.toml")
MPM_MLS = Path("verification/mpm-vibration/mls.toml")
MPM_A01 = Path("verification/mpm-vibration/vibration_a01.toml")
MPM_BSPLINE_CPGIMP = Path("verification/mpm-vibration/bspline_cpgimp.toml")
# Every check of the options study reads the errors at T/4 (where u and the stress peak): its runs
# stop there. Run to T, they took four times as long for the same table (REPORT.md at 1440967:
# 2225 s of its 4143).
MPM_OPTIONS_QUARTER = ["dynamics.end_time=0.005", "dynamics.error_times=[1.0]"]
MPM_OPTIONS_QUICK = ["study.cells=[8,16]"] + MPM_OPTIONS_QUARTER


def mpm_options(ctx: Context) -> Section:
    """The update (USF, velocity Verlet) and mapping (lumped, pseudo-inverse) of quadratic and
    cubic B-splines and lCPDI, B-splines averaged over cpGIMP's domains, and the MLS
    reconstruction with the quadratic basis, the pseudo-inverse and Verlet, against plain
    quadratic B-splines (USF, lumped) at A = 0.05 and 0.1: displacement errors at T/4 on 8-64
    cells."""
    sets = MPM_OPTIONS_QUICK if ctx.quick else MPM_OPTIONS_QUARTER
    plain_a01 = ['study.methods=["bspline"]', "study.particles_per_cell=[9]"]
    a01 = ["exact.amplitude=0.1"]
    # The scene's study (quadratic and cubic, lumped) and the quadratic one with the pseudo-inverse.
    pinv = ['study.methods=["bspline_cpgimp"]', 'study.mappings=["pseudo_inverse"]']
    runs = {0.05: [(MPM_MAPPING, "mpm_options/mapping", sets), (MPM_MLS, "mpm_options/mls_a005", sets),
                   (MPM_BSPLINE_CPGIMP, "mpm_options/bspline_cpgimp_a005", sets),
                   (MPM_BSPLINE_CPGIMP, "mpm_options/bspline_cpgimp_pinv_a005", sets + pinv)],
            0.1: [(MPM_A01, "mpm_options/plain_a01", sets + plain_a01),
                  (MPM_MLS, "mpm_options/mls_a01", sets + a01),
                  (MPM_BSPLINE_CPGIMP, "mpm_options/bspline_cpgimp_a01", sets + a01),
                  (MPM_BSPLINE_CPGIMP, "mpm_options/bspline_cpgimp_pinv_a01", sets + a01 + pinv)]}
    if ctx.quick:  # one amplitude: the machinery, not the verdict
        runs = {0.05: runs[0.05]}
    period = vibration_constants(ctx)["period"]
    series: dict[tuple, list[dict]] = {}
    commands, failed = [], []
    for amplitude, studies in runs.items():
        for scene, name, extra in studies:
            run = ctx.mfree_run("converge", scene, name, extra)
            commands.append(ctx.command("converge", scene, extra))
            rows = read_csv(run.folder / "mpm_convergence.csv")
            failed += [f"A = {amplitude}, {r['method']} {r['update']} {r['mapping']} {r['cells']} cells: {r['status']}"
                       for r in rows if r["status"] != "ok"]
            mls = "quadratic MLS, " if scene == MPM_MLS else ""
            for r in at_time([r for r in rows if r["status"] == "ok"], period / 4):
                label = f"{r['method']} ({mls}{r['update']}, {r['mapping']})"
                series.setdefault((amplitude, label), []).append(r)
    for rs in series.values():
        rs.sort(key=lambda r: int(r["cells"]))
    cells = sorted({int(r["cells"]) for rs in series.values() for r in rs})
    lines, verdicts, observed = [], [], []
    for (amplitude, label), rs in series.items():
        by_cells = {int(r["cells"]): number(r["displacement"]) for r in rs}
        rates = series_rates(rs, "displacement")
        lines.append([f"{amplitude:g}", label] + [by_cells.get(n, "—") for n in cells]
                     + [", ".join(rate_text(x) for x in rates), seconds_text(sum(number(r["seconds"]) for r in rs))])
    for amplitude in runs:
        plain = next((rs for (a, label), rs in series.items() if a == amplitude and label.startswith("bspline (usf, lumped")), None)
        mls = next((rs for (a, label), rs in series.items() if a == amplitude and "quadratic MLS" in label), None)
        if plain and mls:
            p = {int(r["cells"]): number(r["displacement"]) for r in plain}
            m = {int(r["cells"]): number(r["displacement"]) for r in mls}
            common_cells = [n for n in cells if n in p and n in m]
            verdicts += [m[n] <= p[n] for n in common_cells]
            observed.append(f"A = {amplitude}: " + ", ".join(f"{n}: {p[n] / m[n]:.1f}x" for n in common_cells))
    # B-splines averaged over the domains keep converging from 32 to 64 cells, where
    # point-evaluated ones stall.
    domain_rates, domain_verdicts = [], []
    for (amplitude, label), rs in series.items():
        if label.startswith("bspline_cpgimp"):
            rate = mpm_pair_rate(rs, 32, 64)
            domain_rates.append(f"A = {amplitude:g}, {label}: 32→64 {rate_text(rate)}")
            domain_verdicts.append(None if rate is None else meets(rate, 2))
    figure = plot_mpm_options(ctx, series, list(runs))
    failed_text = ("**Failed runs**: " + "; ".join(failed) + "\n\n") if failed else ""
    md = f"""**Problem.** The MPM vibration of section 6 at A = 0.05 and 0.1, 9 particles per cell, dt = 1e-5 s,
with the options that change the time update and the particle-to-grid mapping
(verification/mpm-vibration/README.md): `update = "verlet"` (velocity Verlet with the grid velocities of
the half-kicked particles at their midpoint positions, second order in time) against USF, and
`mapping = "pseudo_inverse"` (seed 004's option 2: nodal values that fit the particle data in least
squares through the consistent mass matrix) against the lumped mapping; the MLS-reconstructed
B-spline MPM with the quadratic basis on 1.5 cells, the pseudo-inverse with the short-wave mass filter
(`mass_filter = 0.3`, which holds the grid's short modes over long runs) and Verlet (`mls.toml`); and
quadratic and cubic B-splines averaged over cpGIMP's particle domains instead of evaluated at the
particles (`bspline_cpgimp.toml`, Verlet).

**Expected**: Verlet removes the time error that USF leaves at the finest grids (lCPDI and cubic
B-splines); the pseudo-inverse lowers the error where it is the projection's; the MLS
configuration's error is at or below plain quadratic B-splines (USF, lumped) at every grid and both
amplitudes; point-evaluated B-splines stall at 64 cells, where the particles' quadrature of the
internal force sets the error, and the domain averages, which integrate the B-splines exactly over
the domains, keep converging (rate ≥ {2 - TOLERANCE:g} from 32 to 64 cells).

**Observed**: RMS displacement error over the particles at T/4 (rates between consecutive grids;
wall time of the configuration's runs, which stop at T/4){" — in quick mode A = 0.05 only, on 8 and 16 cells" if ctx.quick else ""}:

{table(["A", "configuration"] + [f"{n} cells" for n in cells] + ["rates", "wall"], lines)}
Plain quadratic B-splines (USF, lumped) against the quadratic MLS configuration, error ratio per grid:
{"; ".join(observed) if observed else "not run"}.

B-splines averaged over the domains, rate from 32 to 64 cells: {"; ".join(domain_rates) if domain_rates else "not run"}.

{failed_text}{ctx.image(figure, "MPM options: displacement error at T/4 against cell size")}
**Reproduce**:

{commands_block(*commands)}"""
    return Section("", md, [("MPM: quadratic MLS + pseudo-inverse + Verlet against plain B-splines, u at T/4",
                             "at or below at every grid, both amplitudes", "; ".join(observed),
                             verdict(verdicts if verdicts else [None])),
                            ("MPM: B-splines averaged over the domains (Verlet), u rate at T/4, 32→64 cells",
                             f"≥ {2 - TOLERANCE:g}: quadratic and cubic (lumped), quadratic (pseudo-inverse), both amplitudes",
                             "; ".join(domain_rates), verdict(domain_verdicts if domain_verdicts else [None]))])


def plot_mpm_options(ctx: Context, series: dict, amplitudes: list[float]) -> Path:
    """u at T/4 against cell size, one panel per amplitude, one line per configuration."""
    fig, axes = new_figure(len(amplitudes))
    labels = sorted({label for _, label in series})
    for ax, amplitude in zip(axes, amplitudes):
        for (a, label), rs in series.items():
            if a != amplitude:
                continue
            style = "s-" if "MLS" in label else ("o--" if "pseudo" in label else "o-")
            ax.plot([number(r["spacing"]) for r in rs], [number(r["displacement"]) for r in rs], style,
                    color=f"C{labels.index(label) % 10}", label=label)
        log_axes(ax, "cell size h", f"RMS displacement error at T/4, A = {amplitude}", invert_x=True)
    legend_outside(axes[-1])
    return save_figure(fig, ctx.figure("mpm_options_error_vs_cell_size"))


# ---------------------------------------------------------------------------------------------
# 7. Work-precision


def work_precision(ctx: Context) -> Section:
    """Error against wall time, every method on one plot per problem: the cantilever's relative L2
    displacement error, and the vibration's relative displacement error at T/4 for the meshfree
    method and every MPM method; which method reaches 1e-2, 1e-3 and 1e-4 first."""
    headlines, parts = [], []
    cantilever = ctx.data.get("cantilever")
    if cantilever is None:
        parts.append("The cantilever study did not complete; no cantilever work-precision data.\n")
    else:
        figure = plot_cantilever_work(ctx, cantilever)
        text, lines = cantilever_work(cantilever, ctx.data.get("cantilever_one_thread", []))
        parts.append(text + "\n" + ctx.image(figure, "Cantilever: relative L2 displacement and energy errors "
                                                     "against solve time; solid lattice, dashed perturbed"))
        headlines += lines

    vibration, mpm = ctx.data.get("vibration"), ctx.data.get("mpm")
    if vibration is None and mpm is None:
        parts.append("Neither vibration study completed; no vibration work-precision data.\n")
    else:
        constants = vibration_constants(ctx)
        runs, curves = vibration_runs(vibration or [], mpm or [], constants)
        figure = plot_vibration_work(ctx, curves)
        end = "T/4" if ctx.quick else "T"
        parts.append(f"""### Vibration

Relative displacement error at T/4 = RMS displacement error / A (A = {constants["amplitude"]}: at T/4 the
exact |u| has RMS value A over the unit square) against the wall time of the whole run to {end} reported
by mfree, for the meshfree total-Lagrangian runs and every MPM method of the two vibration studies.
**The two families measure the RMS differently**: MPM errors are RMS over the particles (seed 000
eq. 43), meshfree errors RMS over the body, integrated by independent Gauss cells; both estimate the
same L2 norm of the error divided by √|Ω|.
{"" if vibration is not None else "(The meshfree vibration study did not complete.)"}
{"" if mpm is not None else "(The MPM vibration study did not complete.)"}

{fastest_table(runs)}
{ctx.image(figure, "Vibration: relative displacement error at T/4 against wall time, meshfree and MPM")}""")
        headlines += fastest_headlines("vibration", runs)

    md = ("**What is measured.** For each problem, every run of the refinement studies above as one point "
          "(error, wall time), one line per method; the table gives, for each target relative error, the "
          "quickest run that reaches it (`fastest()`: the least time among runs with error ≤ target). "
          "Run times are single measurements on a shared machine (see the header for the thread count).\n\n"
          + "\n".join(parts)
          + "\n**Reproduce**: the data are those of the cantilever (small deformation), meshfree vibration "
            "and MPM vibration studies; re-run those.\n")
    return Section("", md, headlines)


def cantilever_runs(rows: list[dict], norm: str) -> list[tuple[str, float, float]]:
    """(label, relative error in `norm`, solve seconds) of every cantilever run that solved."""
    return [(f"{r['scheme']}, {r['order']} RK, {r['cloud']}, h = {r['spacing']}", number(r[norm]),
             number(r["seconds"])) for r in rows if r["dofs"].strip()]


# deal.II 9.4, Q2 elements, UMFPACK, one thread, the same cantilever: seconds to a relative
# energy error of 1e-3 and 1e-4. Quoted: measured once, in an earlier session on a machine of
# this kind (2 cores), not by this report; whether they include deal.II's error computation is
# not recorded.
DEAL_II_Q2 = {1e-3: 0.025, 1e-4: 0.35}


def cantilever_work(rows: list[dict], one_thread: list[dict]) -> tuple[str, list[tuple]]:
    """The cantilever's work-precision tables in both norms: the fastest run per target, the
    fastest consistent scheme against uncorrected Gauss cells on the perturbed cloud, and the
    time to an energy error against deal.II's Q2."""
    text = ("### Cantilever\n\nRelative L2 displacement and energy errors against the solve time reported by "
            "mfree (setup, quadrature, assembly and solve; error measurement excluded), every quadrature and "
            "RK order on lattice and perturbed clouds (section 3's runs, and in full mode Gauss cells with and "
            "without VCI one level finer on the perturbed cloud, h = 0.1875). Consistent schemes (passing the "
            f"patch test to round-off on every cloud, section 2): {', '.join(QUADRATURE_NAMES.get(c, c) for c in CONSISTENT)}.\n")
    headlines, duel = [], []
    for norm, name in (("l2_displacement", "L2 displacement"), ("energy", "energy")):
        runs = cantilever_runs(rows, norm)
        text += f"\nFastest to a relative {name} error, every run:\n\n" + fastest_table(runs)
        headlines += fastest_headlines(f"cantilever, {name}", runs)
        irregular = [r for r in runs if "perturbed" in r[0]]
        for target in TARGETS:
            ours = fastest([r for r in irregular if r[0].split(",")[0] in CONSISTENT], target)
            gauss = fastest([r for r in irregular if r[0].startswith("gauss_cells,")], target)
            if ours is None and gauss is None:
                ahead = "— (neither reached)"
            else:
                ahead = "yes" if ours is not None and (gauss is None or ours[2] < gauss[2]) else "no"
            duel.append([name, f"{target:.0e}"] + (["not reached", "—"] if ours is None else [ours[0], f"{ours[2]:.3g}"])
                        + (["not reached", "—"] if gauss is None else [gauss[0], f"{gauss[2]:.3g}"]) + [ahead])
    text += ("\nOn the perturbed cloud, the fastest consistent run against the fastest run of uncorrected Gauss "
             "cells (which stall there, section 3):\n\n"
             + table(["norm", "target", "consistent: fastest run", "seconds", "Gauss cells: fastest run", "seconds",
                      "consistent ahead"], duel))
    decided = [d for d in duel if not d[-1].startswith("—")]
    headlines.append(("Cantilever, perturbed cloud: a consistent scheme reaches every target (1e-2 to 1e-4, "
                      "L2 and energy) before uncorrected Gauss cells", "yes at every target either reaches",
                      f"{sum(d[-1] == 'yes' for d in decided)} of {len(decided)}"
                      + (f" ({len(duel) - len(decided)} reached by neither)" if len(decided) < len(duel) else ""),
                      verdict([d[-1] == "yes" for d in decided] or [False])))
    lattice = [r for r in cantilever_runs(one_thread, "energy") if r[0].split(",")[0] in CONSISTENT]
    q2 = []
    for target, seconds in DEAL_II_Q2.items():
        ours = fastest(lattice, target)
        q2.append([f"{target:.0e}", f"{seconds:g}", f"{5 * seconds:g}"]
                  + (["not reached", "—", "no"] if ours is None
                     else [ours[0], f"{ours[2]:.3g}", "yes" if ours[2] <= 5 * seconds else "no"]))
    text += ("\nOn the lattice, the fastest consistent run to a relative energy error, **on one thread** "
             "(`OMP_NUM_THREADS=1`; the lattice runs of section 3 again, solve time without the error "
             "measurement), against deal.II 9.4's Q2 elements (UMFPACK, one thread), the target being within 5× "
             "of it. **The deal.II times are quoted, not measured by this report**: measured once in an earlier "
             "session on a machine of this kind; whether they include deal.II's error computation is not "
             "recorded.\n\n" + table(["energy error", "deal.II Q2 [s], quoted", "5× [s]",
                                       "mfree, one thread: fastest consistent run", "seconds", "within 5×"], q2))
    headlines.append(("Cantilever, lattice, one thread: time to energy error 1e-3 and 1e-4 within 5× of deal.II Q2 "
                      "(0.025 s, 0.35 s, quoted)", "≤ 0.125 s and ≤ 1.75 s",
                      "; ".join(f"{r[0]}: {r[4]} s" for r in q2), verdict([r[-1] == "yes" for r in q2])))
    return text, headlines


def vibration_runs(meshfree: list[dict], mpm: list[dict], constants: dict):
    """(label, relative error, seconds) of every run at T/4, and the curves to plot by method."""
    quarter = constants["period"] / 4
    a = constants["amplitude"]
    runs, curves = [], defaultdict(list)
    for r in at_time(meshfree, quarter):
        method = f"meshfree {r['time_scheme']}"
        label = f"{method}, h = 1/{1 / number(r['spacing']):g}"
        runs.append((label, number(r["displacement"]) / a, number(r["seconds"])))
        curves[method].append(runs[-1])
    for r in at_time(mpm, quarter):
        method = f"MPM {r['method']}, {r['particles_per_cell']} ppc"
        runs.append((f"{method}, {r['cells']} cells", number(r["displacement"]) / a, number(r["seconds"])))
        curves[method].append(runs[-1])
    return runs, curves


def fastest_table(runs: list[tuple[str, float, float]]) -> str:
    """For each target error, the quickest run that reaches it."""
    lines = []
    for target in TARGETS:
        best = fastest(runs, target)
        lines.append([f"{target:.0e}"] + (["not reached", "—", "—"] if best is None
                                          else [best[0], num(best[1]), f"{best[2]:.3g}"]))
    return table(["target relative error", "fastest run", "its error", "seconds"], lines)


def fastest_headlines(problem: str, runs: list[tuple[str, float, float]]) -> list[tuple]:
    """The fastest-run table as summary rows (observations: no verdict)."""
    lines = []
    for target in TARGETS:
        best = fastest(runs, target)
        observed = "not reached" if best is None else f"{best[0]}: {num(best[1])} in {best[2]:.3g} s"
        lines.append((f"Fastest to relative error {target:.0e}, {problem}", "—", observed, "—"))
    return lines


def plot_cantilever_work(ctx: Context, rows: list[dict]) -> Path:
    """Relative L2 displacement and energy errors against solve time, every quadrature, order and cloud."""
    fig, axes = new_figure(2, width=6.0, height=5.0)
    colours = {}
    for (cloud, order, scheme), rs in group([r for r in rows if r["dofs"].strip()], ("cloud", "order", "scheme"),
                                            "spacing", descending=True, key_order=quadrature_order).items():
        colour = colours.setdefault((scheme, order), f"C{len(colours) % 10}")
        for ax, norm in zip(axes, ("l2_displacement", "energy")):
            ax.plot([number(r["seconds"]) for r in rs], [number(r[norm]) for r in rs], CLOUD_STYLE[cloud],
                    marker=CLOUD_MARK[cloud], color=colour, label=f"{scheme}, {order}, {cloud}")
    for ax, name in zip(axes, ("L2 displacement", "energy")):
        for target in TARGETS:
            ax.axhline(target, color="grey", lw=0.5)
        log_axes(ax, "solve time [s]", f"relative {name} error")
    legend_outside(axes[-1])
    return save_figure(fig, ctx.figure("cantilever_error_vs_time"))


def plot_vibration_work(ctx: Context, curves: dict) -> Path:
    """Relative displacement error at T/4 against run time, meshfree and every MPM method."""
    fig, axes = new_figure(1, width=8.0, height=5.5)
    ax = axes[0]
    meshfree_colours = {"meshfree central_difference": "black", "meshfree newmark": "dimgrey"}
    for method, runs in curves.items():  # each curve coarse to fine
        if method in meshfree_colours:
            style, marker, colour = "-", "o", meshfree_colours[method]
        else:  # "MPM <method>, <n> ppc": colour by method, line style by particles per cell
            name, ppc = method.split()[1].rstrip(","), method.split()[2]
            style, marker, colour = ("--" if ppc == "9" else ":"), "s", f"C{position(name, MPM_METHODS)}"
        ax.plot([r[2] for r in runs], [r[1] for r in runs], style, marker=marker, color=colour, label=method)
    for target in TARGETS:
        ax.axhline(target, color="grey", lw=0.5)
    log_axes(ax, "wall time of the run [s]", "relative displacement error at T/4")
    legend_outside(ax)
    return save_figure(fig, ctx.figure("vibration_error_vs_time"))
