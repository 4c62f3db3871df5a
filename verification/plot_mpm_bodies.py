"""Figures of the MPM body cases (verification/mpm-disks, mpm-bar, mpm-column,
mpm-block-collapse) from the runs their run.sh made, one folder per run (named
METHOD or METHOD_CELLS) under RESULTS.

Usage: /usr/bin/python3 plot_mpm_bodies.py CASE RESULTS
  CASE  disks   energy.csv: total kinetic, strain and their sum, and |total momentum| through
                time per method; the energy lost by t_end and the largest momentum
        bar     energy.csv: v_cm(t) = momentum_x / mass against v0 / (beta L) cos(omega t);
                the period from the zero crossings of v_cm and the largest v_cm error
        column  particles.csv: sigma_yy(Y) against -rho g (H - Y); the largest error over
                0.1 H < Y < 0.9 H relative to rho g H
        block   energy.csv: kinetic, strain, work of gravity and the balance through time;
                the largest drift relative to the largest kinetic + strain
Prints a Markdown table (for the case's README) and writes CASE.png into RESULTS.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return [{k: float(v) if k != "body" else v for k, v in r.items()} for r in csv.DictReader(f)]


def runs(results, name):
    out = []
    for run in sorted(os.listdir(results)):
        path = os.path.join(results, run, name)
        if os.path.exists(path):
            out.append((run, read(path)))
    return out


def disks(results, ax):
    print("| method | kinetic + strain lost by t_end | kinetic at t_end / at 0 | largest |total momentum| / one disk's |")
    print("|---|---|---|---|")
    ax2 = ax.twinx()
    for run, rows in runs(results, "energy.csv"):
        t = [r["time"] for r in rows]
        e = [r["kinetic"] + r["strain"] for r in rows]
        p = [math.hypot(r["momentum_x"], r["momentum_y"]) for r in rows]
        one = math.hypot(rows[0]["lower.momentum_x"], rows[0]["lower.momentum_y"])
        (line,) = ax.plot(t, [x / e[0] for x in e], label=f"{run}: kinetic + strain")
        ax.plot(t, [r["kinetic"] / e[0] for r in rows], ":", color=line.get_color())
        ax2.semilogy(t, [max(q / one, 1e-18) for q in p], "--", color=line.get_color(), lw=0.8)
        print(f"| {run} | {100 * (1 - e[-1] / e[0]):.2f} % | {rows[-1]['kinetic'] / rows[0]['kinetic']:.3f} | "
              f"{max(p) / one:.1e} |")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("energy / initial (solid: kinetic + strain, dotted: kinetic)")
    ax.set_ylim(0.0, 1.15)  # a method gaining more than 15 % leaves the axes: see the table
    ax2.set_ylabel("|total momentum| / one disk's (dashed)")
    ax.set_title("Colliding disks: energy and momentum")


def bar(results, ax):
    L, v0, c, rho, thickness = 25.0, 0.1, 10.0, 1.0, 3.125
    beta = math.pi / (2 * L)
    omega = beta * c
    amplitude = v0 / (beta * L)
    exact = 2 * math.pi / omega
    print("| method, cells along the bar | period | period error | largest v_cm error / amplitude |")
    print("|---|---|---|---|")
    mass = rho * L * thickness
    for run, rows in runs(results, "energy.csv"):
        t = [r["time"] for r in rows]
        v = [r["momentum_x"] / mass for r in rows]
        crossings = [t[k] + (t[k + 1] - t[k]) * v[k] / (v[k] - v[k + 1])
                     for k in range(len(v) - 1) if (v[k] > 0) != (v[k + 1] > 0)]
        period = 2 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
        error = max(abs(vk - amplitude * math.cos(omega * tk)) for tk, vk in zip(t, v))
        ax.plot(t, v, label=run)
        print(f"| {run} | {period:.4f} | {100 * (period / exact - 1):+.3f} % | {error / amplitude:.2e} |")
    tt = [k * t[-1] / 400 for k in range(401)]
    ax.plot(tt, [amplitude * math.cos(omega * s) for s in tt], "k:", label="exact")
    ax.set_xlabel("t")
    ax.set_ylabel("v_cm")
    ax.set_title(f"Vibrating bar: centre-of-mass velocity (exact period {exact:.4f})")


def column(results, ax):
    rho, g, H = 1000.0, 10.0, 1.0
    print("| method | largest abs(sigma_yy - exact) / (rho g H), 0.1 H < Y < 0.9 H | over the whole column |")
    print("|---|---|---|")
    for run, rows in runs(results, "particles.csv"):
        y = [r["Y"] for r in rows]
        s = [r["syy"] for r in rows]
        err = [abs(sk + rho * g * (H - yk)) / (rho * g * H) for yk, sk in zip(y, s)]
        inner = max(e for e, yk in zip(err, y) if 0.1 * H < yk < 0.9 * H)
        ax.plot(s, y, ".", ms=3, label=run)
        print(f"| {run} | {100 * inner:.2f} % | {100 * max(err):.2f} % |")
    ax.plot([-rho * g * H, 0.0], [0.0, H], "k-", lw=0.8, label="-rho g (H - Y)")
    ax.set_xlabel("sigma_yy [Pa]")
    ax.set_ylabel("Y [m]")
    ax.set_title("Column under gravity: sigma_yy at the particles")


def block(results, ax):
    print("| method | largest abs(E(t) - E(0)) / max(kinetic + strain) | work of gravity at t_end [J/m] |")
    print("|---|---|---|")
    for run, rows in runs(results, "energy.csv"):
        t = [r["time"] for r in rows]
        scale = max(r["kinetic"] + r["strain"] for r in rows)
        drift = [(r["total"] - rows[0]["total"]) / scale for r in rows]
        ax.plot(t, drift, label=run)
        print(f"| {run} | {max(abs(d) for d in drift):.2e} | {rows[-1]['external_work']:.4e} |")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("(E(t) - E(0)) / max(kinetic + strain)")
    ax.set_title("Collapsing block: kinetic + strain - work of gravity")


def main():
    case, results = sys.argv[1], sys.argv[2]
    fig, ax = plt.subplots(figsize=(9, 5))
    {"disks": disks, "bar": bar, "column": column, "block": block}[case](results, ax)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    name = os.path.join(results, f"{case}.png")
    fig.savefig(name, dpi=110)
    print(f"wrote {name}")


if __name__ == "__main__":
    main()
