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
# the contact in one call: sigma, mu, psi of the pair and E* from E and nu
p, report = egw.contact_from_topography(one, one, radius=R, E1=E, nu1=nu, E2=E, nu2=nu,
                                        model="EP-GW", hardness=H, hardness_coeff=K)
s = topo.mccool(both)
assert p.sigma == s.sigma_summits and report.y_s == s.mean_summit_height
E_star = p.modulus
print(f"R = {R:.4g} m, E* = {E_star:.4g} Pa")
print(f"mu = {p.mu:.4g}, psi = {p.psi:.4g} (K = {K}, H = {H:.3g} Pa); "
      f"GW plasticity index (E*/H) sqrt(sigma/beta) = "
      f"{E_star / H * math.sqrt(p.sigma / report.summit_radius):.4g}; "
      f"y_s = {report.y_s:.4g} m ({report.estimate}: {report.reason})")
hertz = p.replace(model="Hertz", psi=0.0)
for d in (0.0, 5 * p.sigma, 20 * p.sigma):
    r = egw.solve(p, d)
    f_h = egw.hertz(hertz, d)[0]
    print(f"delta = {d:.3e} m: EP-GW force {r.force:.4e} N (Hertz {f_h:.4e} N)")
