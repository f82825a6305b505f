#!/usr/bin/env python3
"""The worked example of doc/parameters.md: GW parameters of two ground steel spheres
from the spectral moments of their surfaces, then mu and psi by the egw library.

    make python && .venv/bin/python tools/worked_example.py
"""
import math

import egw
from egw import topography as topo

# one ground steel surface: rms height 0.2 um, rms slope 0.05, rms curvature 5e4 1/m
# (profile moments m0 = <z^2>, m2 = <z'^2>, m4 = <z''^2>)
one = topo.Moments(m0=(0.2e-6) ** 2, m2=0.05 ** 2, m4=(5.0e4) ** 2)
both = one + one  # the sum surface of two independent surfaces: the moments add
E, nu, H, K = 210e9, 0.3, 7.0e9, 0.6
R1 = R2 = 5e-3
R = R1 * R2 / (R1 + R2)
E_star = 1 / ((1 - nu ** 2) / E + (1 - nu ** 2) / E)

print(f"one surface: alpha = {one.alpha:.3g}")
for label, m in (("one surface", one), ("sum surface", both)):
    s = topo.mccool(m)
    print(f"{label}: m0 = {m.m0:.4g} m^2, m2 = {m.m2:.4g}, m4 = {m.m4:.4g} 1/m^2, "
          f"alpha = {s.alpha:.4g}")
    print(f"  eta = {s.summit_density:.4g} 1/m^2, beta = {s.summit_radius:.4g} m, "
          f"sigma_s = {s.sigma_summits:.4g} m (surface rms {s.sigma_surface:.4g} m), "
          f"mean summit height y_s = {s.mean_summit_height:.4g} m")
    for w in s.warnings:
        print(f"  WARNING: {w}")
s = topo.mccool(both)
mu = egw.mu_from_summits(s.summit_density, s.summit_radius, s.sigma_summits, R)
psi = egw.psi_from_hardness(E_star, H, s.sigma_summits, s.summit_radius, K)
print(f"R = {R:.4g} m, E* = {E_star:.4g} Pa")
print(f"mu = {mu:.4g}, psi = {psi:.4g} (K = {K}, H = {H:.3g} Pa); "
      f"GW plasticity index (E*/H) sqrt(sigma/beta) = "
      f"{E_star / H * math.sqrt(s.sigma_summits / s.summit_radius):.4g}")
p = egw.Params(model="EP-GW", radius=R, modulus=E_star, sigma=s.sigma_summits, mu=mu,
               psi=psi, hardness_coeff=K)
for d in (0.0, 5 * s.sigma_summits, 20 * s.sigma_summits):
    r = egw.solve(p, d)
    f_h = egw.hertz(p.replace(model="Hertz"), d)[0]
    print(f"delta = {d:.3e} m: EP-GW force {r.force:.4e} N (Hertz {f_h:.4e} N)")
