#!/usr/bin/python3
"""The constants of the composite thick sphere under internal pressure (two_layer_sphere.toml).

In each layer u_r = A r + B / r^2 and sigma_rr = 3 K A - 4 mu B / r^3 (K the bulk modulus, mu
the shear modulus of its law). Four conditions fix A1, B1 (inner layer) and A2, B2 (outer):
sigma_rr(a) = -p on the bore, sigma_rr(b) = 0 outside, u_r and sigma_rr continuous at r = c.
Prints the four as the scene's [constants] lines.
"""
import numpy as np

p, a, c, b = 1.0, 1.0, 1.5, 2.0


def moduli(young, poisson):
    return young / (3 * (1 - 2 * poisson)), young / (2 * (1 + poisson))


k1, mu1 = moduli(1000.0, 0.3)
k2, mu2 = moduli(200.0, 0.35)
conditions = np.array([
    [3 * k1, -4 * mu1 / a**3, 0, 0],
    [0, 0, 3 * k2, -4 * mu2 / b**3],
    [c, 1 / c**2, -c, -1 / c**2],
    [3 * k1, -4 * mu1 / c**3, -3 * k2, 4 * mu2 / c**3],
])
values = np.linalg.solve(conditions, [-p, 0, 0, 0])
for name, value in zip(["A1", "B1", "A2", "B2"], values):
    print(f"{name} = {value!r}")
