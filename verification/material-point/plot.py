#!/usr/bin/python3
"""Plots of the material-point tests (README.md), from the path.csv of each run.

usage: plot.py UNIAXIAL_FOLDER TENSION_SHEAR_FOLDER
  UNIAXIAL_FOLDER/uniaxial.png            sigma_yy and sigma_xx against eps_yy = F_yy - 1, and
                                          alpha against t
  TENSION_SHEAR_FOLDER/tension_shear.png  sigma_xy, sigma_yy and sigma_xx against t, and alpha
Each PNG is written to a temporary file and renamed into place.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(folder):
    with open(os.path.join(folder, "path.csv")) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def first_yield(p):
    """Index of the first row with alpha > 0 (None when the path stays elastic)."""
    return next((i for i, a in enumerate(p["alpha"]) if a > 0.0), None)


def save(fig, path):
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)
    plt.close(fig)


def uniaxial(folder):
    p = load(folder)
    strain = [f - 1.0 for f in p["F_yy"]]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))
    left.plot(strain, p["sigma_yy"], "-", color="C0", label="sigma_yy")
    left.plot(strain, p["sigma_xx"], "--", color="C1", label="sigma_xx = sigma_zz")
    k = first_yield(p)
    if k is not None:
        left.plot(strain[k], p["sigma_yy"][k], "o", color="C3", label="first yield")
    # Reverse yield: alpha grows again after the elastic unloading that follows t = 1.
    turn = max(range(len(p["time"])), key=lambda i: -strain[i])
    reverse = next((i for i in range(turn + 1, len(strain)) if p["alpha"][i] > p["alpha"][turn]), None)
    if reverse is not None:
        left.plot(strain[reverse], p["sigma_yy"][reverse], "s", color="C3", label="reverse yield")
    left.axhline(0.0, color="0.6", lw=0.6)
    left.axvline(0.0, color="0.6", lw=0.6)
    left.set_xlabel("eps_yy = F_yy - 1")
    left.set_ylabel("Cauchy stress [MPa]")
    left.set_title("uniaxial strain: J2, linear isotropic + kinematic hardening")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    right.plot(p["time"], p["alpha"], color="C2")
    right.set_xlabel("t")
    right.set_ylabel("alpha (equivalent plastic strain)")
    right.set_title("alpha: loading, elastic unloading, reverse yield")
    right.grid(True, alpha=0.3)
    save(fig, os.path.join(folder, "uniaxial.png"))


def tension_shear(folder):
    p = load(folder)
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))
    left.plot(p["time"], p["sigma_yy"], "-", color="C0", label="sigma_yy")
    left.plot(p["time"], p["sigma_xx"], "--", color="C1", label="sigma_xx = sigma_zz")
    left.plot(p["time"], p["sigma_xy"], "-", color="C3", label="sigma_xy")
    left.axvline(1.0, color="0.6", lw=0.6)
    left.set_xlabel("t (tension for t < 1, shear at constant F_yy for t > 1)")
    left.set_ylabel("Cauchy stress [MPa]")
    left.set_title("tension, then shear: J2, linear isotropic + kinematic hardening")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    right.plot(p["time"], p["alpha"], color="C2")
    right.axvline(1.0, color="0.6", lw=0.6)
    right.set_xlabel("t")
    right.set_ylabel("alpha (equivalent plastic strain)")
    right.set_title("alpha")
    right.grid(True, alpha=0.3)
    save(fig, os.path.join(folder, "tension_shear.png"))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    uniaxial(sys.argv[1])
    tension_shear(sys.argv[2])
    print(f"wrote {os.path.join(sys.argv[1], 'uniaxial.png')}, {os.path.join(sys.argv[2], 'tension_shear.png')}")


if __name__ == "__main__":
    main()
