#!/usr/bin/env python3
"""References of test rough_cap_hysteresis's "GW, E-GW + cap: unloading solves whose levels
stalled" (issue 32, doc/stability.md "Stop 49 (tbl15)"): two unloading solves of the
normalised contact E* = 1, sigma = 1, mu 4, p_y = 0.01 E* that stalled inside egw-table's
hysteresis builds on main bc77115 (histories at rel_tol 1e-4, the build's), here from
scratch by egw.solve_unload (its history tighter), an independent, finer computation:

  GW + cap, R = 2.0264e7 (sigma/delta_y = 2e-4): delta 30799.81 after 53127.42. main's
      automatic levels stall at every rel_tol (residual 0.25), so on fixed meshes
      (n_radial 513, 1025, 2049: no levels, no fallback), the finest the reference and
      the last difference its uncertainty.
  E-GW + cap, R = 4.0528e7 (sigma/delta_y = 1e-4): delta 48510.95 after 92499.38, at
      rel_tol 1e-7.
  E-GW + cap, R = 2.0264e8 (sigma/delta_y = 2e-5): delta 164294 after 324999 (test
      "E-GW + cap at sigma/delta_y = 2e-5: a wide unloaded centre"; doc/stability.md
      "Stop 50 (tiny16)"), at rel_tol 1e-6 and 1e-7 (measured 5e-10 apart).

usage: EGW_LIBRARY=/path/to/libegw.so python3 rough_cap_stalls.py
(measured with main bc77115's libegw of the project venv; the 2e-5 case with the venv's
libegw of 2026-11-30 14:40 UTC, the GW 1e-4 cases below with main f47caf8's)
"""
import egw

GW = ("GW", 40528473.45693511 / 2, 5.3127423456516532e04, 3.0799813320482648e04)
EGW = ("E-GW", 81056946.91387022 / 2, 9.2499375140498625e04, 4.8510945547667710e04)
EGW_WIDE = ("E-GW", 405284734.5693511 / 2, 324999.0, 164294.0)


def params(model, r):
    return egw.Params(model=model, radius=r, modulus=1.0, sigma=1.0, mu=4.0,
                      flow_pressure=0.01)


def report(label, case, opts):
    model, r, m, d = case
    p = params(model, r)
    try:
        top = egw.solve(p, m, opts)
        un = egw.solve_unload(p, d, m, opts)
    except egw.NotConvergedError as exc:
        print(f"{label}: not converged ({exc})")
        return
    print(f"{label}: P(m) = {top.force:.10e} (est {top.est_rel_err:.1e}), "
          f"P(delta, m) = {un.force:.10e} (est {un.est_rel_err:.1e})", flush=True)


report("E-GW, rel_tol 1e-7", EGW, egw.Options(rel_tol=1e-7))
for tol in (1e-6, 1e-7):
    report(f"E-GW 2e-5, rel_tol {tol:g}", EGW_WIDE, egw.Options(rel_tol=tol))
report("GW, rel_tol 1e-7", GW, egw.Options(rel_tol=1e-7))
for n in (513, 1025, 2049):
    report(f"GW, n_radial {n}", GW, egw.Options(n_radial=n))

# GW + cap at sigma/delta_y = 1e-4 (R = 4.0528e7, issue 32, doc/stability.md "Stop 50
# (gw16)"): three unloading solves of egw-table's build (TOL 1e-3) that stalled on main
# f47caf8 at the build's rel_tol 1e-4 (the locating solve, residual 0.78, 0.12, 0.14), and
# a fourth that main answered 5e-4 off under an estimate of 4.2e-5 (78759 -> 65764), on
# fixed meshes (n_radial 1025, 2049; history on the same mesh), the finest the reference.
GW4 = [("GW", 81056946.91387022 / 2, 6.5012269369623180e04, 5.3532025905558483e04),
       ("GW", 81056946.91387022 / 2, 7.8759202027217383e04, 6.5020730641208109e04),
       ("GW", 81056946.91387022 / 2, 1.2e05, 1.0346772315096174e05),
       ("GW", 81056946.91387022 / 2, 7.8759202027217383e04, 6.5763933692726496e04)]
for case in GW4:
    for n in (1025, 2049):
        report(f"GW 1e-4, {case[2]:.6e} -> {case[3]:.6e}, n_radial {n}", case,
               egw.Options(n_radial=n))
