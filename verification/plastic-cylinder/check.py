"""The plastic thick cylinder against the classical solution (SPEC section 10).

Usage: /usr/bin/python3 check.py load_steps.csv OUTPUT_FOLDER [P_OVER_PL_AT_FACTOR_1]

Reads the load steps of `mfree run cylinder.toml` (load factor, probe displacement u_r(a), area of the
plastic zone) and prints, per step, the pressure p / p_L, the elastic-plastic radius
c = sqrt(a^2 + 4 A_p / pi) of the quarter annulus's plastic area A_p against Hill's
p = (sigma_y / sqrt 3) [2 ln(c / a) + 1 - c^2 / b^2], and the Newton iterations. Writes
cylinder.png: the pressure against u_r(a) with the first-yield and limit pressures, and c
against the pressure with the classical curve.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

A, B, SY = 1.0, 2.0, 1.0
P_LIMIT = 2 * SY / math.sqrt(3) * math.log(B / A)


def hill_pressure(c):
    return SY / math.sqrt(3) * (2 * math.log(c / A) + 1 - c * c / (B * B))


def hill_radius(p):
    """c(p) by bisection; None below first yield."""
    if p <= hill_pressure(A):
        return None
    lo, hi = A, B
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if hill_pressure(mid) < p else (lo, mid)
    return 0.5 * (lo + hi)


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    out = sys.argv[2]
    top = float(sys.argv[3]) if len(sys.argv) > 3 else 0.98  # p / p_L at load factor 1
    print(f"p_L = {P_LIMIT:.6f}, first yield at p / p_L = {hill_pressure(A) / P_LIMIT:.4f}")
    print(f"{'p/p_L':>7} {'u_r(a)':>11} {'c mfree':>9} {'c Hill':>9} {'error':>8} {'Newton':>6}")
    worst = 0.0
    p_of, u_of, c_num, c_exact = [0.0], [0.0], [], []
    for r in rows:
        p = top * float(r["load_factor"])
        area = float(r["plastic_area"])
        c = math.sqrt(A * A + 4 * area / math.pi) if area > 0 else None
        ch = hill_radius(p * P_LIMIT)
        err = ""
        if c is not None and ch is not None:
            worst = max(worst, abs(c - ch) / ch)
            err = f"{(c - ch) / ch:+8.2%}"
            c_num.append((p, c))
        p_of.append(p)
        u_of.append(float(r["probe_ux"]))
        print(f"{p:7.4f} {u_of[-1]:11.4e} {c if c else 0:9.4f} {ch if ch else 0:9.4f} {err:>8} {r['iterations']:>6}")
    print(f"largest relative error of the elastic-plastic radius: {worst:.2%}")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    left.plot(u_of, p_of, "-o", ms=3, label="mfree (J2, Newton)")
    left.axhline(1.0, color="k", ls="--", label="limit load $p_L = (2\\sigma_y/\\sqrt{3})\\,\\ln(b/a)$")
    left.axhline(hill_pressure(A) / P_LIMIT, color="gray", ls=":", label="first yield")
    left.set_xlabel("radial displacement $u_r(a)$")
    left.set_ylabel("$p / p_L$")
    left.legend()
    left.grid(True, alpha=0.3)
    ps = [hill_pressure(A) / P_LIMIT + k * (top - hill_pressure(A) / P_LIMIT) / 200 for k in range(201)]
    right.plot(ps, [hill_radius(p * P_LIMIT) or A for p in ps], "k-", label="classical (Hill)")
    right.plot([p for p, _ in c_num], [c for _, c in c_num], "o", ms=4, label="mfree: $\\sqrt{a^2 + 4A_p/\\pi}$")
    right.set_xlabel("$p / p_L$")
    right.set_ylabel("elastic-plastic radius $c$")
    right.legend()
    right.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{out}/cylinder.png", dpi=120)
    print(f"wrote {out}/cylinder.png")


if __name__ == "__main__":
    main()
