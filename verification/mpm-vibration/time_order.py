#!/usr/bin/env python3
"""Order in time of an MPM update scheme on the vibration problem (A = 0.05, to T/4).

Runs `mfree run` on vibration.toml at time steps 4e-5, 2e-5, 1e-5 and 5e-6 s and at the
reference 1.25e-6 s, all on the same grid, and prints the RMS difference of the particle
positions and velocities from the reference run, with the observed rates. A first-order
scheme halves the difference with the step, a second-order one quarters it.

    /usr/bin/python3 verification/mpm-vibration/time_order.py --method bspline --update verlet --cells 16
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
STEPS = [4e-5, 2e-5, 1e-5, 5e-6]
REFERENCE = 1.25e-6


def run(mfree, scene, method, update, mapping, cells, dt, folder):
    args = [mfree, "run", scene, "--set", f"mpm.method={method}", "--set", f"mpm.update={update}",
            "--set", f"mpm.mapping={mapping}", "--set", f"mpm.cells={cells}", "--set", f"dynamics.time_step={dt}",
            "--set", "dynamics.end_time=0.005", "--set", "dynamics.error_times=[1.0]", "--set", "dynamics.frames=0",
            "--set", "output.fields=[]", "--set", "output.vtk=false", "--set", "output.particles_csv=true",
            "--set", f"output.folder={folder}"]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "particles.csv")) as f:
        return [(float(r["x"]), float(r["y"]), float(r["vx"]), float(r["vy"])) for r in csv.DictReader(f)]


def rms(a, b, k):
    return math.sqrt(sum((p[k] - q[k]) ** 2 + (p[k + 1] - q[k + 1]) ** 2 for p, q in zip(a, b)) / len(a))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--method", default="bspline")
    parser.add_argument("--update", default="verlet")
    parser.add_argument("--mapping", default="lumped")
    parser.add_argument("--cells", type=int, default=16)
    parser.add_argument("--mfree", default=os.path.join(ROOT, "build", "mfree"))
    a = parser.parse_args()
    scene = os.path.join(HERE, "vibration.toml")
    with tempfile.TemporaryDirectory() as tmp:
        out = lambda dt: os.path.join(tmp, f"dt{dt:g}")
        reference = run(a.mfree, scene, a.method, a.update, a.mapping, a.cells, REFERENCE, out(REFERENCE))
        print(f"{a.method}, {a.update}, {a.mapping}, {a.cells} cells: differences at T/4 from dt = {REFERENCE:g} s")
        print(f"{'dt [s]':>8} {'x [m]':>10} {'rate':>5} {'v [m/s]':>10} {'rate':>5}")
        last = None
        for dt in STEPS:
            state = run(a.mfree, scene, a.method, a.update, a.mapping, a.cells, dt, out(dt))
            ex, ev = rms(state, reference, 0), rms(state, reference, 2)
            rates = ("-", "-") if last is None else (f"{math.log2(last[0] / ex):.2f}", f"{math.log2(last[1] / ev):.2f}")
            print(f"{dt:8.2g} {ex:10.3e} {rates[0]:>5} {ev:10.3e} {rates[1]:>5}")
            last = (ex, ev)
    return 0


if __name__ == "__main__":
    sys.exit(main())
