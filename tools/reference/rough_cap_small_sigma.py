#!/usr/bin/env python3
"""Reference of test rough_cap_hysteresis's "E-GW + cap at sigma/delta_y = 2e-4" (issue 32,
doc/stability.md "Stop 48 (tbl14)"): the unloading force of the normalised contact
R = 2.0264e7 sigma, E* = 1, sigma = 1, mu = 4, p_y = 0.01 E* (delta_y = 5000 sigma) at
delta = 29257.97 after delta_max = 53124.70 (the solve whose Newton stalled inside the
table build on main c5b1f11), and the loading force at delta_max, both by egw.solve /
egw.solve_unload at rel_tol 1e-7 from a cold start (no table: an independent, finer
computation than the build's warm-started solves at rel_tol 1e-4 of the table's tol).

usage: EGW_LIBRARY=/path/to/libegw.so python3 rough_cap_small_sigma.py
"""
import egw

R = 40528473.45693511 / 2
M = 53124.701157277108
D = 29257.973240289983

p = egw.Params(model="E-GW", radius=R, modulus=1.0, sigma=1.0, mu=4.0, flow_pressure=0.01)
opts = egw.Options(rel_tol=1e-7)
top = egw.solve(p, M, opts).force
un = egw.solve_unload(p, D, M, opts).force
print(f"P(m) = {top:.10e}")
print(f"P(delta, m) = {un:.10e}")
