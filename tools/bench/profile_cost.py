#!/usr/bin/env python3
"""Cost of the pressure profiles (issue 32): egw.profile (100 radii) against egw.solve, and
egw.profile(..., delta_max=) against egw.solve_unload, for Hertz + cap at 2, 5, 20 delta_y
(unloading at 0.9 delta_max) and EP-GW psi 2 (delta 4 after 10 sigma); best of 5 (3) calls,
single-threaded. solve_unload reuses its kept history (a sweep); a profile loads its own.

Run: OMP_NUM_THREADS=1 python tools/bench/profile_cost.py
"""
import time, numpy as np, egw, math
p = egw.Params(model="Hertz", radius=1.0, modulus=1.0, flow_pressure=2/math.pi)
r = np.linspace(0, 3, 100)
def t(f, n=5):
    best = 1e9
    for _ in range(n):
        t0 = time.perf_counter(); f(); best = min(best, time.perf_counter() - t0)
    return best
for d in (2.0, 5.0, 20.0):
    ts = t(lambda: egw.solve(p, d)); tp = t(lambda: egw.profile(p, d, r))
    tu = t(lambda: egw.solve_unload(p, 0.9*d, d)); tpu = t(lambda: egw.profile(p, 0.9*d, r, delta_max=d))
    print(f"Hertz+cap delta={d}: solve {ts*1e3:.1f} ms, profile(100 r) {tp*1e3:.1f} ms (x{tp/ts:.1f}); solve_unload {tu*1e3:.1f} ms, profile_unload {tpu*1e3:.1f} ms (x{tpu/tu:.1f})")
q = egw.Params(model="EP-GW", sigma=1.0, mu=4.0, psi=2.0, hardness_coeff=0.6)
rr = np.linspace(0, math.sqrt(2*q.radius*20), 100)
ts = t(lambda: egw.solve_unload(q, 4.0, 10.0), 3); tp = t(lambda: egw.profile(q, 4.0, rr, delta_max=10.0), 3)
print(f"EP-GW psi 2, 4 after 10 sigma: solve_unload {ts*1e3:.1f} ms, profile_unload {tp*1e3:.1f} ms (x{tp/ts:.1f})")
