"""Time of a sphere solve with a tabulated rough-flat law against today's classic-GW solve
of the same pair (issue 31 goal: within +-20 %), in one run, interleaved, best of 5.

GW's own law p_G(d) is tabulated (egw.flat_pressure at 901 nodes, -4..14 sigma, exact
slopes) and solved with egw_solve_flat_law; the GW solve is egw_solve. Same R, E*, sigma,
rel_tol 1e-6, one thread.
    .venv/bin/python tools/bench/flat_law_solve_time.py
"""
import time

import numpy as np

import egw

p = egw.Params(model="GW", radius=1e-3, modulus=1e9, sigma=1e-6, mu=4.0)
u = 1e-6 * np.linspace(-4, 14, 901)
pg, dpg = egw.flat_pressure(p, u, derivative=True)
law = egw.FlatLaw.from_table(u, pg, dpdu=dpg, length=1e-6, modulus=1e9)
pl = egw.Params(radius=1e-3, modulus=1e9, flat_law=law)
opts = egw.Options(rel_tol=1e-6, n_threads=1)
deltas = 1e-6 * np.array([-2.0, 0.0, 1.0, 5.0])
best = {"GW": np.inf, "law": np.inf}
for _ in range(5):
    for name, params in (("GW", p), ("law", pl)):
        t = time.perf_counter()
        for d in deltas:
            egw.solve(params, float(d), opts)
        best[name] = min(best[name], (time.perf_counter() - t) / len(deltas))
print(f"GW solve {best['GW'] * 1e3:.3f} ms, tabulated-law solve {best['law'] * 1e3:.3f} ms, "
      f"ratio {best['law'] / best['GW']:.3f} (delta/sigma -2, 0, 1, 5; best of 5)")
