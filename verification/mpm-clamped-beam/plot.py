"""The clamped beam's particles at the end (particles.csv of run.sh's E = 1e5 Pa runs),
coloured by sigma_xx, one panel per method: results/mpm-clamped-beam/beam.png."""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

out = Path(sys.argv[1])
methods = ["bspline", "bspline_mls", "cpdi"]
fig, axes = plt.subplots(1, 3, figsize=(13, 4))
for ax, method in zip(axes, methods):
    d = np.genfromtxt(out / f"{method}_1e5" / "particles.csv", delimiter=",", names=True, dtype=None, encoding=None)
    ax.scatter(d["x"], d["y"], c=d["sxx"], s=3, cmap="coolwarm")
    ax.axvline(0.0, color="k", lw=2)
    ax.set_title(f"{method}, t = 1 s")
    ax.set_aspect("equal")
    ax.set_xlim(-0.02, 1.0)
    ax.set_ylim(0.0, 0.8)
fig.suptitle("A soft cantilever (E = 1e5 Pa) against a fixed wall: point particles leave it, lCPDI's domains hold")
fig.tight_layout()
fig.savefig(out / "beam.png", dpi=90)
print(f"wrote {out / 'beam.png'}")
