"""Shift references of rough + cap unloading near the residual overlap (issue 32, stop 47).

Reads the CSV of `fpm run --example small-sigma-shift` (E-GW + cap, mu 4, R = E* = 1,
p_y = 2/pi, from 2 delta_y: the rough model's discrete unloading solves at sigma_j/delta_y
= 1e-5 .. 2e-4 and their shifts D_j, P_cap(delta + D_j) = P_j). For each overlap, of each
sigma_j the solve at the tightest rel_tol that converged; d_j = D_j/x_j,
x_j = (sigma_j/sigma)**(2/3), fitted by least squares as a polynomial of degree 1, 2, 3 in
x_j and evaluated at x = 1 (the target sigma): D. Prints D per degree, the fraction of
delta_max of delta + D (for tools/reference/cap_near_residual.py --at, the independent
smooth cap), and the force's relative uncertainty 1.5 |D_3 - D_1| / (delta + D - delta_r)
(P_cap ~ (delta - delta_r)**(3/2) there).

    python tools/reference/shift_reference.py shift.csv [--sigma 1e-6]
"""
import argparse
import csv

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("--sigma", type=float, default=1e-6)
    args = ap.parse_args()
    delta_max = 2.0
    residual = None
    best = {}
    with open(args.csv) as f:
        for row in csv.reader(f):
            if not row:
                continue
            if row[0] == "residual" and int(row[1]) == 400:
                residual = float(row[4])
            if row[0] != "rough":
                continue
            sigma, frac, tol = float(row[1]), float(row[2]), float(row[3])
            try:   # (Fortran writes -huge, no shift, without its exponent letter)
                force, shift = float(row[4]), float(row[7])
            except ValueError:
                continue
            if force <= 0 or shift < -1:
                continue
            key = (frac, sigma)
            if key not in best or tol < best[key][0]:
                best[key] = (tol, shift)
    print("fraction,n,degree,D,fraction_shifted,force_uncertainty")
    for frac in sorted({k[0] for k in best}, reverse=True):
        rows = sorted((k[1],) + v for k, v in best.items() if k[0] == frac)
        sig = np.array([r[0] for r in rows])
        shift = np.array([r[2] for r in rows])
        x = (sig / args.sigma) ** (2.0 / 3.0)
        fits = {}
        for deg in (1, 2, 3):
            if len(x) > deg + 1:
                fits[deg] = float(np.polyval(np.polyfit(x, shift / x, deg), 1.0))
        if len(fits) < 3:
            continue
        gap = frac * delta_max + fits[2] - residual
        unc = 1.5 * abs(fits[3] - fits[1]) / gap
        for deg, d in fits.items():
            print(f"{frac:.4f},{len(x)},{deg},{d:.6e},{frac + d / delta_max:.13f},{unc:.2e}")


if __name__ == "__main__":
    main()
