#!/usr/bin/env python3
"""References of test rough_cap_hysteresis's "E-GW + cap at sigma/delta_y = 1e-5 to 2e5
sigma: builds, within rel_tol" (issue 32, doc/stability.md "Stop 51 (tiny17)"): unloading
forces of the normalised contact E* = 1, sigma = 1, mu 4, p_y = 0.01 E*, R = 4.0528e8
(sigma/delta_y = 1e-5, delta_y = 1e5), at three (turning point, overlap) pairs inside the
table's reach (0 .. 2e5 = 2 delta_y), each from scratch by egw.solve_unload at rel_tol 1e-7
(its history tighter still): an independent, finer computation than the table's solves
(rel_tol 1e-4), and P(m), the loading force at the turning point (the table's measure).

usage: [EGW_LIBRARY=/path/to/libegw.so] python3 rough_cap_tiny_table.py
(measured with the project venv's libegw, main 6922da8)
"""
import egw

R = 810569469.1387022 / 2
POINTS = [(133373.881, 130706.651), (133373.881, 93365.433), (166718.772, 83367.149)]


def main():
    p = egw.Params(model="E-GW", radius=R, modulus=1.0, sigma=1.0, mu=4.0,
                   flow_pressure=0.01)
    for tol in (1e-6, 1e-7):
        opts = egw.Options(rel_tol=tol)
        for m, d in POINTS:
            top = egw.solve(p, m, opts)
            un = egw.solve_unload(p, d, m, opts)
            print(f"rel_tol {tol:g}: m {m} delta {d}: P(m) {top.force:.10e} "
                  f"P {un.force:.10e} (estimate {un.est_rel_err:.1e})", flush=True)


if __name__ == "__main__":
    main()
