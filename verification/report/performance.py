"""Performance: what a run computes and how its stages scale with threads.

Every run prints and writes (summary.json) its stage table: wall seconds and the number of
times each stage ran. Two sections read those tables:

    only what the scene needs   runs that ask for less (no fields, no MLS, a linear material)
                                must not run the stages they do not need, and the set-up stages
                                (clouds, shape functions, weights and projection) run once per
                                run however many load or time steps reuse them
    thread scaling              the same runs with OMP_NUM_THREADS = 1 and 2, stage by stage
    direct and Krylov solvers   the cantilever at growing size with CHOLMOD and with CG + GAMG
                                (stiffness and consistency node system), stage by stage
    MPM step speed              particle-steps per second of every MPM method, update and
                                mapping at 64^2 cells and 9 particles per cell, 1 and 2
                                threads (build/mfree_bench, Google Benchmark)
"""
from __future__ import annotations

import json
import os
import subprocess

from common import (CANTILEVER, LARGE_DEFORMATION, MPM_VIBRATION, QUIET, VIBRATION, Context, RunResult, Section,
                    new_figure, save_figure, table)


REPEATS = 3  # runs per thread count in the scaling table (best of)

# Stages that prepare the discretisation: computed once, reused by every load or time step.
SET_UP = ["clouds", "shape functions", "boundary functions", "weights and projection", "consistency"]


def sections(ctx: Context) -> list[Section]:
    out = []
    with ctx.step("performance: only what the scene needs"):
        out.append(only_what_is_needed(ctx))
    with ctx.step("performance: thread scaling"):
        out.append(thread_scaling(ctx))
    with ctx.step("performance: direct and Krylov solvers"):
        out.append(solver_scaling(ctx))
    with ctx.step("performance: MPM step speed"):
        out.append(mpm_step_speed(ctx))
    return out


def stages(run: RunResult) -> dict[str, tuple[float, int]]:
    """name -> (seconds, calls) of a run's stage table (empty for a failed run)."""
    if not run.ok or not run.summary:
        return {}
    return {s["name"]: (s["seconds"] or 0.0, s["calls"]) for s in run.summary["stages"]}


def stage_table(runs: dict[str, RunResult]) -> str:
    """One row per stage (in order of first appearance), one column per run: seconds (calls)."""
    names: list[str] = []
    for r in runs.values():
        names += [n for n in stages(r) if n not in names]
    rows = []
    for n in names:
        row = [n]
        for r in runs.values():
            s = stages(r).get(n)
            row.append("—" if s is None else f"{s[0]:.3g} s ({s[1]})")
        rows.append(row)
    rows.append(["**total**"] + [f"**{r.summary['total_seconds']:.3g} s**" if r.ok and r.summary else "failed"
                                 for r in runs.values()])
    return table(["stage"] + list(runs), rows)


def only_what_is_needed(ctx: Context) -> Section:
    title = "Only what the scene needs"
    h = 1.5 if ctx.quick else 0.75
    dyn = ["nodes.spacing=0.0625" if ctx.quick else "nodes.spacing=0.03125", "dynamics.end_time=0.005",
           "dynamics.error_times=[1.0]"]
    mpm = ["mpm.cells=16" if ctx.quick else "mpm.cells=32", "dynamics.end_time=0.002", "dynamics.error_times=[1.0]",
           "dynamics.frames=0"]
    meshfree = {
        "cantilever, fields + VTK": ctx.mfree_run("run", CANTILEVER, "performance/needs/cantilever_fields", [f"nodes.spacing={h}"]),
        "cantilever, no output": ctx.mfree_run("run", CANTILEVER, "performance/needs/cantilever_quiet", QUIET + [f"nodes.spacing={h}"]),
        "Neo-Hookean, Newton": ctx.mfree_run("run", LARGE_DEFORMATION, "performance/needs/newton", QUIET + [f"nodes.spacing={h}"]),
        "vibration, no output": ctx.mfree_run("run", VIBRATION, "performance/needs/vibration_quiet",
                                              QUIET + dyn + ["dynamics.frames=0"]),
        "vibration, no output, no energy": ctx.mfree_run("run", VIBRATION, "performance/needs/vibration_no_energy",
                                                         QUIET + dyn + ["dynamics.frames=0", "dynamics.energy_every=0"]),
        "vibration, 5 frames": ctx.mfree_run("run", VIBRATION, "performance/needs/vibration_frames",
                                             dyn + ["dynamics.frames=5"]),
    }
    particles = {
        "MPM B-spline": ctx.mfree_run("run", MPM_VIBRATION, "performance/needs/mpm_bspline", QUIET + mpm),
        "MPM B-spline + MLS": ctx.mfree_run("run", MPM_VIBRATION, "performance/needs/mpm_mls",
                                            QUIET + mpm + ["mpm.method=bspline_mls"]),
        "MPM CPDI": ctx.mfree_run("run", MPM_VIBRATION, "performance/needs/mpm_cpdi", QUIET + mpm + ["mpm.method=cpdi"]),
    }

    checks = []

    def check(what: str, ok: bool) -> None:
        checks.append([what, "yes" if ok else "no"])

    st = {k: stages(r) for k, r in {**meshfree, **particles}.items()}
    check("no fields asked for: no `output` stage (stress recovery and writing skipped)",
          "output" in st["cantilever, fields + VTK"] and "output" not in st["cantilever, no output"]
          and "output" not in st["vibration, no output"] and "output" in st["vibration, 5 frames"])
    check("no energy balance asked for (`energy_every = 0`): no `energy` stage, the same `residual` calls "
          "(central differences need the applied forces anyway)",
          "energy" in st["vibration, no output"] and "energy" not in st["vibration, no output, no energy"]
          and st["vibration, no output, no energy"].get("residual", (0, 0))[1]
          == st["vibration, no output"].get("residual", (0, -1))[1])
    check("a linear material: one assembly, one factorisation, one solve (no Newton iterations)",
          all(st["cantilever, no output"].get(s, (0, 0))[1] == 1 for s in ("assembly", "factorisation", "solve")))
    newton_factorisations = st["Neo-Hookean, Newton"].get("factorisation", (0, 0))[1]
    check(f"set-up stages ({', '.join(SET_UP)}) run once in every meshfree run, though the Newton run "
          f"factorises {newton_factorisations} times and the vibration takes "
          f"{meshfree['vibration, no output'].summary['steps'] if meshfree['vibration, no output'].summary else '?'} steps",
          all(calls == 1 for name in SET_UP for k in meshfree for (s, calls) in [st[k].get(name, (0, 1))]))
    check("`MLS functions` run only when the scene asks for MLS reconstruction",
          "MLS functions" in st["MPM B-spline + MLS"] and "MLS functions" not in st["MPM B-spline"]
          and "MLS functions" not in st["MPM CPDI"])
    steps = particles["MPM B-spline"].summary["steps"] if particles["MPM B-spline"].summary else None
    check("MPM: every stage runs once per step (weights are recomputed because particles move)",
          steps is not None and all(c == steps for (_, c) in st["MPM B-spline"].values()))
    all_ok = all(c[1] == "yes" for c in checks)
    body = ("Stage tables (wall seconds and, in brackets, how many times the stage ran) of runs that ask for "
            "different things. Each `mfree run` prints this table and writes it to summary.json.\n\n"
            f"Meshfree: the cantilever at h = {h} with all fields written to VTK and with none, the Neo-Hookean "
            "cantilever by Newton with load steps, and the vibration problem (central differences, 1/4 period) "
            "without output, without output or energy balance, and with 5 VTK frames.\n\n" + stage_table(meshfree)
            + "\nMPM: the vibration problem (0.002 s) with quadratic B-splines, with MLS reconstruction, and "
              "with CPDI.\n\n" + stage_table(particles)
            + "\nChecks on these tables:\n\n" + table(["check", "holds"], checks)
            + "\nShape functions and their projected gradients are computed once per run (the set-up "
              "stages above) and reused by every load step, Newton iteration and time step: the "
              "total-Lagrangian residual and tangent evaluate stresses at the quadrature points from the "
              "stored gradients. The MPM weights are recomputed every step because the particles move.\n")
    return Section(title, body, [("Only what the scene needs, nothing twice", "stage tables show it",
                                  f"{sum(c[1] == 'yes' for c in checks)}/{len(checks)} checks hold",
                                  "yes" if all_ok else "no")])


def thread_scaling(ctx: Context) -> Section:
    title = "Thread scaling, 1 and 2 threads"
    cases = {
        "cantilever (linear statics)": (CANTILEVER, QUIET + ["nodes.spacing=0.75" if ctx.quick else "nodes.spacing=0.375"]),
        "vibration (total Lagrangian, explicit)": (VIBRATION, QUIET + [
            "nodes.spacing=0.0625" if ctx.quick else "nodes.spacing=0.03125", "dynamics.end_time=0.005",
            "dynamics.frames=0", "dynamics.error_times=[1.0]"]),
        "MPM quadratic B-spline": (MPM_VIBRATION, QUIET + [
            "mpm.cells=32" if ctx.quick else "mpm.cells=64", "dynamics.end_time=0.002", "dynamics.frames=0",
            "dynamics.error_times=[1.0]"]),
        "MPM B-spline + MLS": (MPM_VIBRATION, QUIET + [
            "mpm.method=bspline_mls", "mpm.cells=16" if ctx.quick else "mpm.cells=32", "dynamics.end_time=0.001",
            "dynamics.frames=0", "dynamics.error_times=[1.0]"]),
    }
    rows, bars = [], []
    for label, (scene, sets) in cases.items():
        slug = label.split(" (")[0].replace(" ", "_").replace("+", "plus")
        # Best of REPEATS runs per thread count, stage by stage, as a benchmark would: single
        # runs on this machine drift by 15 % and more.
        best = {}
        for threads in (1, 2):
            runs = [ctx.mfree_run("run", scene, f"performance/threads/{slug}_{threads}_{k}", sets, threads=threads)
                    for k in range(REPEATS)]
            tables = [stages(r) for r in runs if r.ok]
            best[threads] = {name: (min(t[name][0] for t in tables), calls)
                             for name, (_, calls) in (tables[0].items() if tables else [])}
            best[threads, "total"] = min((r.summary["total_seconds"] for r in runs if r.ok and r.summary), default=None)
        s1, s2 = best[1], best[2]
        for name, (t1, calls) in s1.items():
            if name not in s2 or t1 < 1e-3:
                continue  # stages under a millisecond say nothing about scaling
            t2 = s2[name][0]
            rows.append([label, name, calls, t1, t2, f"{t1 / t2:.2f}"])
            bars.append((f"{label.split(' (')[0]}: {name}", t1 / t2))
        if best[1, "total"] and best[2, "total"]:
            t1, t2 = best[1, "total"], best[2, "total"]
            rows.append([f"**{label}**", "**total**", "", t1, t2, f"**{t1 / t2:.2f}**"])
    fig, (ax,) = new_figure(width=8, height=0.28 * max(len(bars), 4) + 1)
    ax.barh([b[0] for b in bars], [b[1] for b in bars], color="tab:blue")
    ax.axvline(1.0, color="k", lw=0.8)
    ax.axvline(2.0, color="k", lw=0.8, ls=":")
    ax.invert_yaxis()
    ax.set_xlabel("speed-up, 2 threads against 1")
    ax.tick_params(axis="y", labelsize=7)
    figure = save_figure(fig, ctx.figure("performance_threads"))
    totals = [r for r in rows if r[1] == "**total**"]
    body = (f"The same runs with OMP_NUM_THREADS = 1 and 2 on this machine ({os.cpu_count()} cores), stage by "
            f"stage (stages under a millisecond left out), each the best of {REPEATS} runs: single runs on this "
            "machine drift by 15 % and more. `build/mfree_bench` (verification/benchmarks/) times the MPM step and "
            "the elasticity stages with Google Benchmark.\n\n"
            + table(["run", "stage", "calls", "1 thread [s]", "2 threads [s]", "speed-up"], rows)
            + "\n" + ctx.image(figure, "Speed-up of every stage from 1 to 2 threads")
            + "\nSerial stages show a speed-up near 1 (the sparse factorisation is CHOLMOD's or UMFPACK's "
              "own; the light MPM grid stages are bound by memory bandwidth).\n")
    observed = "; ".join(f"{r[0].strip('*').split(' (')[0]} {r[5].strip('*')}x" for r in totals)
    return Section(title, body, [("Two threads against one (whole runs)", "up to 2x", observed, "—")])


def solver_scaling(ctx: Context) -> Section:
    """The cantilever (linear RK, projected quadrature, symmetric correction) at growing size,
    every linear solve by CHOLMOD or by CG + GAMG: the stages the solver touches and the
    errors, which must agree."""
    title = "Direct and Krylov solvers at growing size"
    spacings = [0.75, 0.375] if ctx.quick else [0.375, 0.1875, 0.10714285714285714]
    kinds = ["cholmod", "cg"]
    rows, times = [], {k: [] for k in kinds}
    errors = {}
    for h in spacings:
        for kind in kinds:
            r = ctx.mfree_run("run", CANTILEVER, f"performance/solvers/{kind}_{h:.4f}",
                              QUIET + [f"nodes.spacing={h}", "nodes.perturbation=0.0", f'solver.kind="{kind}"'])
            if not r.ok or not r.summary:
                continue
            st = stages(r)
            dofs = r.summary["dofs"]
            total = r.summary["total_seconds"]
            times[kind].append((dofs, total))
            errors[kind, h] = r.summary.get("energy")
            solver = r.summary.get("solver", "")
            iterations = solver.split(", ")[2].split(" ")[0] if kind == "cg" else "–"
            node = r.summary.get("consistency_solver", "")
            node_iterations = node.split(", ")[2].split(" ")[0] if kind == "cg" else "–"
            rows.append([f"{int(dofs)}", kind, st.get("consistency", (0.0,))[0], st.get("factorisation", (0.0,))[0],
                         st.get("solve", (0.0,))[0], total, iterations, node_iterations,
                         f"{errors[kind, h]:.6e}" if errors[kind, h] is not None else "–"])
    fig, (ax,) = new_figure(width=6, height=4)
    for kind, marker in zip(kinds, "os"):
        if times[kind]:
            ax.loglog([t[0] for t in times[kind]], [t[1] for t in times[kind]], marker + "-",
                      label="CHOLMOD" if kind == "cholmod" else "CG + GAMG")
    ax.set_xlabel("DOFs")
    ax.set_ylabel("whole run [s], %d threads" % (os.cpu_count() or 1))
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    figure = save_figure(fig, ctx.figure("performance_solvers"))
    same = [abs(errors["cg", h] - errors["cholmod", h]) <= 1e-4 * errors["cholmod", h]
            for h in spacings if errors.get(("cg", h)) and errors.get(("cholmod", h))]
    agree = bool(same) and all(same)
    body = ("The cantilever of section 4 on a lattice, linear RK, projected quadrature with the symmetric "
            "correction, every linear solve (the stiffness and the node system of the correction) by CHOLMOD or by "
            "CG + GAMG (tolerance 1e-10 on |b - A x| / |b|; `[solver] kind`). Seconds of the stages the solver "
            "touches (`consistency` holds the node system's assembly and solves; `factorisation` is GAMG's setup "
            "for CG), the CG iterations of the stiffness and of one node-system solve, and the relative energy "
            "error, which the two solvers must share.\n\n"
            + table(["DOFs", "solver", "consistency [s]", "factorisation [s]", "solve [s]", "total [s]",
                     "CG iterations", "node-system iterations (2 solves)", "energy error"], rows)
            + "\n" + ctx.image(figure, "Whole-run time against size, CHOLMOD and CG + GAMG")
            + "\nAt larger sizes (verification/benchmarks/README.md): 5·10^5 DOFs take 83 s and 10.5 GB with "
              "CHOLMOD, 72 s and 5.4 GB with CG + GAMG; 10^6 DOFs 144 s and 10.7 GB with CG + GAMG (309 s and "
              "19.4 GB with CHOLMOD). `[solver] kind = \"auto\"` turns to the Krylov methods above "
              "`direct_limit` unknowns.\n")
    return Section(title, body, [("CHOLMOD and CG + GAMG give the same energy error", "to 1e-4 relative",
                                  "yes" if agree else "no", "match" if agree else "differ")])


# ---------------------------------------------------------------------------------------------
# MPM step speed

# mfree_bench's MPM runs (verification/benchmarks/bench_mpm.cpp) and what they are.
MPM_BENCHMARKS = {
    "mpm/classic/usf": "Classic, USF",
    "mpm/ugimp/usf": "uGIMP, USF",
    "mpm/cpgimp/usf": "cpGIMP, USF",
    "mpm/cpdi/usf": "lCPDI, USF",
    "mpm/qcpdi/usf": "qCPDI, USF",
    "mpm/cpdi2/usf": "CPDI2, USF",
    "mpm/bspline2/usf": "quadratic B-spline, USF",
    "mpm/bspline2/usl": "quadratic B-spline, USL",
    "mpm/bspline2/szs": "quadratic B-spline, SZS",
    "mpm/bspline2/usavg": "quadratic B-spline, USAVG",
    "mpm/bspline2/usf/no_body_force": "quadratic B-spline, USF, no body force",
    "mpm/bspline2/usf/j2": "quadratic B-spline, USF, J2 plasticity, no body force",
    "mpm/bspline3/usf": "cubic B-spline, USF",
    "mpm/bspline_cpgimp2/usf": "quadratic B-spline averaged over cpGIMP's domains, USF",
    "mpm/bspline_cpgimp3/usf": "cubic B-spline averaged over cpGIMP's domains, USF",
    "mpm/bspline_mls/usf": "MLS-reconstructed B-spline (linear basis, 1.5 cells), USF",
    "mpm/bspline2/verlet": "quadratic B-spline, Verlet",
    "mpm/cpdi/verlet": "lCPDI, Verlet",
    "mpm/bspline2/usf/pseudo_inverse": "quadratic B-spline, USF, pseudo-inverse",
    "mpm/bspline2/verlet/pseudo_inverse": "quadratic B-spline, Verlet, pseudo-inverse",
    "mpm/bspline_cpgimp2/verlet/pseudo_inverse": "quadratic B-spline averaged over the domains, Verlet, pseudo-inverse",
    "mpm/cpdi/verlet/pseudo_inverse": "lCPDI, Verlet, pseudo-inverse",
    "mpm/bspline_mls_quadratic/verlet/pseudo_inverse": "MLS (quadratic basis), Verlet, pseudo-inverse",
    "mpm/bspline_mls_quadratic/verlet/pseudo_inverse_filtered":
        "MLS (quadratic basis), Verlet, pseudo-inverse with mass_filter 0.3 (mls.toml)",
}
# (MLS run, the plain B-spline run of the same update and mapping) for the cost ratio.
MLS_PAIRS = [("mpm/bspline_mls/usf", "mpm/bspline2/usf"),
             ("mpm/bspline_mls_quadratic/verlet/pseudo_inverse", "mpm/bspline2/verlet/pseudo_inverse"),
             ("mpm/bspline_mls_quadratic/verlet/pseudo_inverse_filtered", "mpm/bspline2/verlet/pseudo_inverse")]


def bench_rates(ctx: Context, threads: int) -> dict[str, float]:
    """Million particle-steps per second of every MPM benchmark with `threads` threads, the best of
    the repetitions (empty when mfree_bench is missing or fails; the failure is recorded)."""
    bench = ctx.mfree.parent / "mfree_bench"
    if not bench.exists():
        ctx.failures.append(f"MPM step speed: {bench} is missing (configure with MFREE_BUILD_BENCHMARKS=ON)")
        return {}
    command = [str(bench), "--benchmark_filter=^mpm/", "--benchmark_format=json",
               f"--benchmark_min_time={0.05 if ctx.quick else 0.5}",
               f"--benchmark_repetitions={1 if ctx.quick else 3}"]
    done = subprocess.run(command, cwd=ctx.root, env=dict(os.environ, OMP_NUM_THREADS=str(threads)),
                          capture_output=True, text=True)
    if done.returncode != 0:
        ctx.failures.append(f"MPM step speed: mfree_bench exited with status {done.returncode}")
        return {}
    rates: dict[str, float] = {}
    for b in json.loads(done.stdout)["benchmarks"]:
        if b.get("run_type") == "aggregate":
            continue
        name = b["run_name"].removesuffix("/real_time")
        rates[name] = max(rates.get(name, 0.0), b["particle_steps_per_second"] / 1e6)
    return rates


def mpm_step_speed(ctx: Context) -> Section:
    title = "MPM step speed, every method"
    rates = {threads: bench_rates(ctx, threads) for threads in (1, 2)}
    reference = rates[2].get("mpm/bspline2/usf")
    rows = []
    for name, label in MPM_BENCHMARKS.items():
        r1, r2 = rates[1].get(name), rates[2].get(name)
        if r1 is None and r2 is None:
            if rates[1] or rates[2]:
                ctx.failures.append(f"MPM step speed: benchmark {name} did not run")
            continue
        rows.append([label, f"`{name}`", f"{r1:.2f}" if r1 else "—", f"{r2:.2f}" if r2 else "—",
                     f"{reference / r2:.2f}" if reference and r2 else "—"])
    ratios = []
    for mls, plain in MLS_PAIRS:
        if rates[2].get(mls) and rates[2].get(plain) and rates[1].get(mls) and rates[1].get(plain):
            ratios.append([MPM_BENCHMARKS[mls], MPM_BENCHMARKS[plain], f"{rates[1][plain] / rates[1][mls]:.2f}",
                           f"{rates[2][plain] / rates[2][mls]:.2f}"])
    fig, (ax,) = new_figure(width=8, height=0.3 * max(len(rows), 4) + 1)
    labels = [r[0] for r in rows]
    for k, threads in enumerate((1, 2)):
        values = [rates[threads].get(name, 0.0) for name in MPM_BENCHMARKS if name in rates[1] or name in rates[2]]
        ax.barh([i + 0.4 * k for i in range(len(values))], values, height=0.4, label=f"{threads} thread(s)")
    ax.set_yticks([i + 0.2 for i in range(len(labels))], labels, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("million particle-steps per second")
    ax.legend(fontsize=7)
    figure = save_figure(fig, ctx.figure("performance_mpm_step"))
    quick = (" Quick mode: one short repetition each, indicative only." if ctx.quick else "")
    body = ("One explicit MPM step of the vibration problem (A = 0.05, its body force and initial velocity, slip "
            "walls) on 64 x 64 cells with 9 particles per cell (36 864 particles), dt = 1e-5 s, timed by "
            "`build/mfree_bench` (verification/benchmarks/bench_mpm.cpp; the solver is built outside the timed "
            "loop), best of 3 repetitions of at least 0.5 s, OMP_NUM_THREADS = 1 and 2." + quick + "\n\n"
            + table(["method", "benchmark", "1 thread [M/s]", "2 threads [M/s]",
                     "cost / quadratic B-spline USF (2 threads)"], rows)
            + "\n**MLS reconstruction against plain quadratic B-splines with the same update and mapping** "
              "(step time ratio):\n\n"
            + table(["MLS run", "plain run", "1 thread", "2 threads"], ratios)
            + "\n" + ctx.image(figure, "MPM particle-steps per second, 64 x 64 cells, 9 particles per cell")
            + "\nReproduce: `OMP_NUM_THREADS=2 build/mfree_bench --benchmark_filter=^mpm/ "
              "--benchmark_counters_tabular=true`\n")
    observed = "; ".join(f"{r[0]}: {r[2]} (1 thread), {r[3]} (2 threads)" for r in ratios)
    return Section(title, body, [("MLS step against the plain B-spline step", "at most 3x", observed,
                                  "—" if ctx.quick or not ratios else
                                  ("yes" if all(float(r[2]) <= 3.0 and float(r[3]) <= 3.0 for r in ratios)
                                   else "no"))])
