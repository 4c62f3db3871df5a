"""Shared pieces of the verification report: running mfree, reading its CSV files, and
writing markdown tables, figures and sections.

Every study module (studies.py, stability.py, performance.py) receives one Context and
returns a list of Section objects; report.py assembles them into REPORT.md.

    ctx.mfree_run("converge", Path("verification/cantilever/cantilever.toml"), "cantilever",
                  sets=["study.spacings=[6.0,3.0]"])
        -> RunResult; the outputs are in ctx.work / "cantilever"

Numbers in tables go through num() ("1.23e-04"); observed rates through rate() and
rate_text() ("1.98").
"""
from __future__ import annotations

import contextlib
import csv
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The verification scenes the report runs (relative to the repository root), and what they share.
CANTILEVER = Path("verification/cantilever/cantilever.toml")
NITSCHE = Path("verification/cantilever/nitsche_sweep.toml")
LARGE_DEFORMATION = Path("verification/cantilever/large_deformation.toml")
LAME = Path("verification/lame/lame.toml")
VIBRATION = Path("verification/vibration/vibration.toml")
MPM_VIBRATION = Path("verification/mpm-vibration/vibration.toml")
MPM_LONG = Path("verification/mpm-vibration/long_run.toml")
MPM_WEDGE = Path("verification/mpm-vibration/wedge_impact.toml")
MPM_METHODS = ["classic", "ugimp", "cpgimp", "cpdi", "qcpdi", "cpdi2", "bspline", "bspline_cubic", "bspline_cpgimp",
               "bspline_cpgimp_cubic", "bspline_mls"]
QUIET = ["output.fields=[]", "output.vtk=false"]  # a sweep point writes no fields

# A run folder name is a relative path of plain components: it is deleted before each run.
_SAFE_NAME = re.compile(r"^[A-Za-z0-9_.-]+(/[A-Za-z0-9_.-]+)*$")
_NONFINITE = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


@dataclass
class RunResult:
    """One mfree call: exit status, captured output, wall time and its output folder."""
    returncode: int
    stdout: str
    stderr: str
    seconds: float
    folder: Path
    summary: dict | None  # folder/"summary.json" if the run wrote one, else None
    command: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.returncode == 0


@dataclass
class Section:
    """One numbered section of REPORT.md and its rows of the summary table."""
    title: str
    markdown: str  # body, without the title line
    headlines: list[tuple[str, str, str, str]] = field(default_factory=list)  # what, expected, observed, verdict


class Context:
    """Where mfree is, where outputs go, and what went wrong so far.

    root     the repository (the working folder of every mfree call)
    out      the folder of REPORT.md; figure links are relative to it
    figures  the folder of the PNG figures
    work     the folder of the raw run outputs, one sub-folder per run
    quick    quick mode: coarse levels only, a few minutes in all
    failures messages of mfree calls that should have succeeded and did not, and of
             studies that could not be completed
    data     results shared between studies (a study that feeds another stores its rows here)
    timings  (label, seconds) of every step timed with step()
    """

    def __init__(self, root: Path, mfree: Path, out: Path, figures: Path, work: Path, quick: bool):
        self.root = Path(root).resolve()
        self.mfree = Path(mfree).resolve()
        self.out = Path(out).resolve()
        self.figures = Path(figures).resolve()
        self.work = Path(work).resolve()
        self.quick = quick
        self.failures: list[str] = []
        self.data: dict[str, object] = {}
        self.timings: list[tuple[str, float]] = []
        self.runs: list[RunResult] = []
        self.tolerated: dict[Path, str] = {}

    def mfree_run(self, subcommand: str, scene: Path, name: str, sets: list[str] = (),
                  threads: int | None = None, expect_failure: bool = False) -> RunResult:
        """Runs `mfree SUBCOMMAND SCENE` with its outputs in work/NAME (emptied first).

        `sets` are scene overrides "section.key=VALUE" (TOML values), passed as --set;
        `integration` has no --set and takes the folder as --out. Never raises on a non-zero
        exit: an unexpected failure is added to `failures` and its stderr printed.
        """
        folder = self._run_folder(name)
        command = [str(self.mfree), subcommand, str(scene)]
        if subcommand == "integration":
            if sets:
                raise ValueError("mfree integration takes no --set overrides")
            command += ["--out", str(folder)]
        else:
            command += ["--set", f"output.folder={json.dumps(str(folder))}"]
            for s in sets:
                command += ["--set", s]
        env = dict(os.environ)
        if threads is not None:
            env["OMP_NUM_THREADS"] = str(threads)
        start = time.perf_counter()
        try:
            done = subprocess.run(command, cwd=self.root, env=env, capture_output=True, text=True)
            returncode, stdout, stderr = done.returncode, done.stdout, done.stderr
        except OSError as e:  # the program could not be started: reported like a failed run
            returncode, stdout, stderr = 127, "", f"cannot run {self.mfree}: {e}"
        seconds = time.perf_counter() - start
        result = RunResult(returncode, stdout, stderr, seconds, folder,
                           _read_summary(folder / "summary.json"), command)
        self.runs.append(result)
        if not result.ok and not expect_failure:
            self.failures.append(f"`{name}`: mfree {subcommand} exited with status {returncode}: "
                                 f"{_last_line(stderr)}")
            print(f"mfree {subcommand} {scene} failed (status {returncode}):", file=sys.stderr)
            print(stderr.rstrip(), file=sys.stderr)
        return result

    def tolerate_failed_rows(self, result: RunResult, reason: str) -> None:
        """Declares that rows of failed runs in this run's CSV files (empty sizes, or a status
        other than "ok") are an expected observation, not an error: their NaN fields are
        listed in the report instead of failing it."""
        self.tolerated[result.folder] = reason

    def figure(self, name: str) -> Path:
        """The path of figure NAME (a PNG) in the figures folder, which is created."""
        self.figures.mkdir(parents=True, exist_ok=True)
        return self.figures / (name if name.endswith(".png") else name + ".png")

    def image(self, path: Path, caption: str) -> str:
        """A markdown image of PATH, linked relative to REPORT.md, with its caption below."""
        link = Path(os.path.relpath(Path(path).resolve(), self.out)).as_posix()
        return f"![{caption}]({link})\n\n*{caption}*\n"

    def command(self, subcommand: str, scene: Path | str, sets: list[str] = ()) -> str:
        """The shell command that reproduces one study from the repository root (outputs go to
        the scene's own folder)."""
        words = ["build/mfree", subcommand, str(scene)]
        for s in sets:
            words += ["--set", s]
        return " ".join(shlex.quote(w) for w in words)

    @contextlib.contextmanager
    def step(self, label: str):
        """Times a block, records it in `timings` and prints one progress line when it ends."""
        start = time.perf_counter()
        try:
            yield
        finally:
            seconds = time.perf_counter() - start
            self.timings.append((label, seconds))
            print(f"  {label:<44} {seconds:8.1f} s", flush=True)

    def _run_folder(self, name: str) -> Path:
        if not _SAFE_NAME.match(name) or ".." in name.split("/"):
            raise ValueError(f"run name {name!r}: use letters, digits, '_', '-', '.' and '/'")
        folder = self.work / name
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir(parents=True)
        return folder


def _read_summary(path: Path) -> dict | None:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def _last_line(text: str) -> str:
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else "(no message)"


# ---------------------------------------------------------------------------------------------
# Reading results


def read_csv(path: Path) -> list[dict]:
    """The rows of a CSV file with a header line, as dictionaries of strings."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text) -> float:
    """A CSV field as a float; an empty or unreadable field is nan."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def failed_row(row: dict) -> bool:
    """True for a row the program wrote for a failed run: a status other than "ok", or
    empty size fields (elasticity studies leave nodes and dofs empty)."""
    if "status" in row:
        return row["status"] != "ok"
    return any(key in row and not row[key].strip() for key in ("nodes", "dofs"))


def nonfinite_fields(path: Path) -> list[tuple[int, str, bool]]:
    """The NaN and infinite fields of a CSV file: (line number, column, in a failed-run row)."""
    found = []
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        for line, fields in enumerate(reader, start=2):
            bad = [i for i, x in enumerate(fields) if x.strip().lower() in _NONFINITE]
            if bad:
                failed = failed_row(dict(zip(header, fields)))
                found += [(line, header[i] if i < len(header) else f"field {i + 1}", failed) for i in bad]
    return found


# ---------------------------------------------------------------------------------------------
# Numbers and tables


def num(x, digits=3) -> str:
    """A number as "1.23e-04" (`digits` significant digits); "—" for None and nan."""
    if x is None:
        return "—"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    x = float(x)
    if math.isnan(x):
        return "—"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:.{max(digits - 1, 0)}e}"


def rate(e_coarse, e_fine, h_coarse, h_fine) -> float:
    """Observed order log(e_c / e_f) / log(h_c / h_f); nan unless both errors are positive."""
    try:
        if e_coarse > 0 and e_fine > 0 and h_coarse > 0 and h_fine > 0 and h_coarse != h_fine:
            return math.log(e_coarse / e_fine) / math.log(h_coarse / h_fine)
    except TypeError:
        pass
    return math.nan


def rate_text(r) -> str:
    """An observed rate with two decimals; "—" when there is none."""
    return "—" if r is None or math.isnan(r) else f"{r:.2f}"


def seconds_text(x) -> str:
    """A run time in seconds with three significant digits ("0.153", "12.4", "298")."""
    x = float(x)
    return "—" if math.isnan(x) else f"{x:.3g}"


def table(header: list[str], rows: list[list]) -> str:
    """A markdown table; floats through num(), None as "—", anything else as str()."""
    def cell(x):
        if isinstance(x, float) or x is None:
            return num(x)
        return str(x).replace("|", "\\|")
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(x) for x in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def fastest(runs: list[tuple[str, float, float]], target: float) -> tuple[str, float, float] | None:
    """Of runs (label, error, seconds), the quickest whose error is at most `target`."""
    reached = [r for r in runs if not math.isnan(r[1]) and r[1] <= target]
    return min(reached, key=lambda r: r[2]) if reached else None


# ---------------------------------------------------------------------------------------------
# Figures


def new_figure(columns: int = 1, width: float = 6.0, height: float = 4.5):
    """A figure with `columns` axes side by side (a list of axes)."""
    fig, axes = plt.subplots(1, columns, figsize=(width * columns, height), squeeze=False)
    return fig, list(axes[0])


def save_figure(fig, path: Path) -> Path:
    """Writes a figure as PNG (temporary file, then rename) and closes it."""
    fig.tight_layout()
    tmp = path.with_name(path.name + ".tmp.png")
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, path)
    plt.close(fig)
    return path


def legend_outside(ax, fontsize: int = 7) -> None:
    """The legend of `ax` to the right of it, clear of the curves."""
    ax.legend(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)


def slope_guide(ax, h_coarse: float, h_fine: float, error: float, order: float) -> None:
    """A grey dashed line of slope `order` from (h_coarse, error) to h_fine, labelled."""
    e_fine = error * (h_fine / h_coarse) ** order
    ax.plot([h_coarse, h_fine], [error, e_fine], color="grey", ls="--", lw=1.0)
    ax.annotate(f"slope {order:g}", (h_fine, e_fine), fontsize=8, color="grey",
                textcoords="offset points", xytext=(4, -10))


def level_ticks(ax, values: list[float], reciprocal: bool = False) -> None:
    """x ticks at the refinement levels only, labelled "0.75" (or "1/64" with `reciprocal`)."""
    from matplotlib.ticker import FixedLocator, NullFormatter, NullLocator
    values = sorted(set(values))
    ax.xaxis.set_major_locator(FixedLocator(values))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xticklabels([f"1/{1 / v:g}" if reciprocal else f"{v:g}" for v in values])


def log_axes(ax, xlabel: str, ylabel: str, invert_x: bool = False, log_x: bool = True) -> None:
    """Log-log (or, with log_x=False, semi-log) axes with labels and a light grid."""
    if log_x:
        ax.set_xscale("log")
    ax.set_yscale("log")
    if invert_x:
        ax.invert_xaxis()
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
