#!/usr/bin/python3
"""mfree verification report: reruns every verification study and writes REPORT.md with
tables, PNG figures and a summary of expected against observed results.

usage (from the repository root; `bash verification/report/run.sh` builds mfree first):

    /usr/bin/python3 verification/report/report.py            full: verification/REPORT.md,
                                                               figures in verification/report/figures/,
                                                               runs in results/report/ (~42 min on 2 cores)
    /usr/bin/python3 verification/report/report.py --quick --out DIR
                                                               coarse levels only (a few minutes):
                                                               DIR/REPORT.md, DIR/figures/, DIR/runs/
    --mfree PATH                                               the program (default build/mfree)

Sections: the convergence studies (studies.py), cracks and interfaces (cracks.py), plasticity
(plasticity.py), solids (solids.py), then stability (stability.py) and performance
(performance.py); each module's sections(ctx) returns a list of common.Section.

Exits with status 1 when an mfree call that should have succeeded failed, a study could not be
completed, a CSV written by a run holds NaN or inf outside runs the study declared as failing,
or a figure the report links to is missing. REPORT.md is written in every case and lists them.
"""
from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import shlex
import subprocess
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import cracks  # noqa: E402
import performance  # noqa: E402
import plasticity  # noqa: E402
import solids  # noqa: E402
import stability  # noqa: E402
import studies  # noqa: E402
from common import Context, Section, nonfinite_fields, table  # noqa: E402


def main() -> int:
    args = parse_arguments()
    start, started = time.perf_counter(), time.time()
    ctx = make_context(args)
    if not usable(ctx.mfree):
        return 2
    print(f"mfree verification report ({'quick' if ctx.quick else 'full'} mode): runs in {ctx.work}", flush=True)

    sections = studies.sections(ctx)
    sections += module_sections(ctx, "Cracks and interfaces", cracks)
    sections += module_sections(ctx, "Plasticity", plasticity)
    sections += module_sections(ctx, "Solids", solids)
    sections += module_sections(ctx, "Stability", stability)
    sections += module_sections(ctx, "Performance", performance)

    body = render_sections(sections)
    problems = list(ctx.failures)
    problems += missing_figures(ctx, body, started)
    nonfinite, tolerated = scan_csv_files(ctx)
    problems += nonfinite
    seconds = time.perf_counter() - start

    report = render_header(ctx, args, seconds, problems, tolerated) + render_summary(sections) + body
    path = ctx.out / "REPORT.md"
    write_atomically(path, report)
    print(f"wrote {path} in {seconds:.0f} s", flush=True)
    for p in problems:
        print(f"problem: {p}", file=sys.stderr)
    return 1 if problems else 0


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description="Rerun every mfree verification study and write REPORT.md.")
    parser.add_argument("--quick", action="store_true", help="coarse levels only: a few minutes")
    parser.add_argument("--out", type=Path, help="folder of REPORT.md, figures/ and work/ "
                                                 "(default: verification/, figures in verification/report/figures/)")
    parser.add_argument("--mfree", type=Path, default=ROOT / "build" / "mfree", help="the mfree program")
    return parser.parse_args()


def make_context(args: argparse.Namespace) -> Context:
    """Output folders: with --out everything goes under it; otherwise the report goes to
    verification/ and the raw runs to results/report/ (results/report-quick/ in quick mode)."""
    if args.out is not None:
        out = args.out.resolve()
        figures, work = out / "figures", out / "runs"
    else:
        out = ROOT / "verification"
        figures = HERE / "figures"
        work = ROOT / "results" / ("report-quick" if args.quick else "report")
    for folder in (out, figures, work):
        folder.mkdir(parents=True, exist_ok=True)
    return Context(ROOT, args.mfree, out, figures, work, args.quick)


def usable(mfree: Path) -> bool:
    """mfree exists and has the --set option the studies rely on."""
    if not (mfree.is_file() and os.access(mfree, os.X_OK)):
        print(f"report: {mfree} is not an executable; build mfree first (bash verification/report/run.sh "
              f"does)", file=sys.stderr)
        return False
    help_text = subprocess.run([str(mfree), "run", "--help"], capture_output=True, text=True).stdout
    if "--set" not in help_text:
        print(f"report: {mfree} has no --set option; rebuild it from this source tree", file=sys.stderr)
        return False
    return True


def module_sections(ctx: Context, name: str, module) -> list[Section]:
    """The sections of one report module; a module that raises becomes one section saying so."""
    with ctx.step(f"{name} sections, total"):
        try:
            return list(module.sections(ctx))
        except Exception as e:  # noqa: BLE001 - the rest of the report is still worth writing
            traceback.print_exc()
            ctx.failures.append(f"{name}: the sections could not be completed ({type(e).__name__}: {e})")
            return [Section(name, f"**The sections could not be completed**: `{type(e).__name__}: {e}`.\n",
                            [(name, "sections complete", "failed", "no")])]


# ---------------------------------------------------------------------------------------------
# Checks


def missing_figures(ctx: Context, markdown: str, started: float) -> list[str]:
    """Images the report links to that do not exist, or are left from an earlier run (older than
    `started`, a time.time() value)."""
    problems = []
    for link in re.findall(r"!\[[^\]]*\]\(([^)\s]+)\)", markdown):
        path = ctx.out / link
        if not path.is_file():
            problems.append(f"figure {link} is linked from the report but missing")
        elif path.stat().st_mtime < started - 1.0:
            problems.append(f"figure {link} was not written by this run (an older file)")
    return problems


def scan_csv_files(ctx: Context) -> tuple[list[str], list[str]]:
    """NaN and inf fields in every CSV under the work folder: (problems, tolerated notes).
    Fields in rows of failed runs are tolerated where the study declared that failing runs are
    an observation (Context.tolerate_failed_rows)."""
    problems, tolerated = [], []
    for path in sorted(ctx.work.rglob("*.csv")):
        found = nonfinite_fields(path)
        if not found:
            continue
        reason = next((why for folder, why in ctx.tolerated.items() if folder in path.parents), None)
        bad = [(line, column) for line, column, failed_run in found if not (failed_run and reason)]
        shown = path.relative_to(ctx.work)
        if bad:
            where = ", ".join(f"line {line} `{column}`" for line, column in bad[:5])
            more = f" and {len(bad) - 5} more" if len(bad) > 5 else ""
            problems.append(f"{shown}: NaN or inf at {where}{more}")
        rows = sorted({line for line, _, failed_run in found if failed_run and reason})
        if rows:
            tolerated.append(f"{shown}: {len(rows)} failed run(s) (lines {', '.join(map(str, rows))}) — {reason}")
    return problems, tolerated


# ---------------------------------------------------------------------------------------------
# Rendering


def render_sections(sections: list[Section]) -> str:
    """The numbered sections; runs of blank lines left by optional paragraphs become one."""
    parts = []
    for i, section in enumerate(sections, start=1):
        body = "\n".join(line.rstrip() for line in section.markdown.strip().splitlines())
        body = re.sub(r"\n{3,}", "\n\n", body)
        parts.append(f"\n## {i}. {section.title}\n\n{body}\n")
    return "".join(parts)


def render_summary(sections: list[Section]) -> str:
    rows = [list(h) for s in sections for h in s.headlines]
    counts = {v: sum(1 for r in rows if r[3] == v) for v in ("yes", "no", "—")}
    return ("\n## Summary\n\n"
            f"{len(rows)} checks: {counts['yes']} match, {counts['no']} do not, {counts['—']} without a verdict "
            "(observations, or not measured in this mode). Criteria are stated in each section.\n\n"
            + table(["what", "expected", "observed", "match"], rows))


def render_header(ctx: Context, args, seconds: float, problems: list[str], tolerated: list[str]) -> str:
    mode = ("quick (coarse levels only; rates are pre-asymptotic and several criteria cannot be checked)"
            if ctx.quick else "full")
    lines = [["mode", mode],
             ["date", datetime.datetime.now().astimezone().isoformat(timespec="seconds")],
             ["commit", git_commit()],
             ["machine", machine()],
             ["threads", threads()],
             ["total time", f"{seconds:.0f} s"],
             ["regenerate", f"`{regenerate_command()}`"]]
    text = "# mfree verification report\n\n" + table(["", ""], lines)
    text += "\nRun time of each study (mfree runs, reading and plotting):\n\n"
    text += table(["study", "seconds"], [[label, f"{s:.1f}"] for label, s in ctx.timings])
    if problems:
        text += "\n**Problems** (the report generator exits with status 1):\n\n" + "".join(f"- {p}\n" for p in problems)
    else:
        text += "\nEvery mfree run that should succeed did, no CSV holds NaN or inf, every figure exists.\n"
    if tolerated:
        text += ("\nRuns reported as failed by mfree inside a study (their CSV rows hold NaN), an expected "
                 "observation:\n\n" + "".join(f"- {t}\n" for t in tolerated))
    return text


def git_commit() -> str:
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                                text=True, check=True).stdout.strip()
        # The report's own outputs (written before this header) do not make the code dirty.
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", ".",
                                ":!verification/REPORT.md", ":!verification/report/figures"], cwd=ROOT,
                               capture_output=True, text=True).stdout.strip()
        return commit + (" (with uncommitted changes)" if dirty else "") if commit else "unknown"
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def machine() -> str:
    model = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores (nproc), {platform.system()} {platform.release()}"


def threads() -> str:
    value = os.environ.get("OMP_NUM_THREADS")
    if value:
        return f"OMP_NUM_THREADS={value}"
    return f"OMP_NUM_THREADS unset: OpenMP uses all {os.cpu_count()} cores"


def regenerate_command() -> str:
    """The command line of this run, from the folder it was started in."""
    value = os.environ.get("OMP_NUM_THREADS")
    python = (f"OMP_NUM_THREADS={value} " if value else "") + "/usr/bin/python3"
    arguments = shlex.join(sys.argv[1:])
    if Path.cwd().resolve() == ROOT:
        return f"{python} verification/report/report.py {arguments}".strip()
    return f"cd {shlex.quote(str(Path.cwd()))} && {python} {shlex.quote(str(HERE / 'report.py'))} {arguments}".strip()


def write_atomically(path: Path, text: str) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


if __name__ == "__main__":
    sys.exit(main())
