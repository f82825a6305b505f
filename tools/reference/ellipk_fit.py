#!/usr/bin/env python3
"""Coefficients of egw_ellip's fast K of the complementary modulus (ellipk_comp_fast):

    K = P(eta) - ln(eta) Q(eta),   eta = kc**2 in (0, 1],  P, Q polynomials of degree 9,

the form of Cody (1965, Math. Comp. 19:105) and Hastings: the logarithmic singularity of K
at kc -> 0 is carried by ln(eta) exactly, so polynomials suffice on the whole interval.
The coefficients are a weighted (relative-error) least-squares fit, in 40-digit mpmath, to
K = pi/(2 AGM(1, kc)) on 400 Chebyshev points in eta plus 60 points with eta from 1e-1 to
1e-30 (the log regime). The script then evaluates the double-precision polynomials by
Horner on a fine grid and prints the largest relative error against mpmath (about 1 ulp).

Run from the repository root: python3 tools/reference/ellipk_fit.py > tools/reference/ellipk_fit.txt
and paste the arrays into src/egw/kernels/ellip.f90.
"""
import sys

try:
    import mpmath
except ImportError:
    import subprocess
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mpmath"])
    import mpmath
from mpmath import mp, mpf

DEGREE = 9


def k_of_eta(eta):
    return mpmath.pi / (2 * mpmath.agm(1, mpmath.sqrt(eta)))


def fit():
    n_cheb = 400
    etas = [(1 - mpmath.cos(mpmath.pi * (j + mpf(1) / 2) / n_cheb)) / 2 for j in range(n_cheb)]
    etas += [mpf(10) ** (-(1 + 29 * mpf(j) / 59)) for j in range(60)]
    rows, rhs = [], []
    for eta in etas:
        k = k_of_eta(eta)
        row = [eta ** i for i in range(DEGREE + 1)]
        row += [-mpmath.log(eta) * eta ** i for i in range(DEGREE + 1)]
        rows.append([v / k for v in row])
        rhs.append(mpf(1))
    x = mpmath.qr_solve(mpmath.matrix(rows), mpmath.matrix(rhs))[0]
    return [float(x[i]) for i in range(DEGREE + 1)], \
        [float(x[DEGREE + 1 + i]) for i in range(DEGREE + 1)]


def horner(c, x):
    s = 0.0
    for v in reversed(c):
        s = s * x + v
    return s


def main():
    mp.dps = 40
    p, q = fit()
    worst = 0.0
    grid = [j / 4000 for j in range(1, 4001)] + [10.0 ** (-j / 2) for j in range(0, 600)]
    for eta in grid:
        import math
        approx = horner(p, eta) - math.log(eta) * horner(q, eta)
        worst = max(worst, abs(approx / float(k_of_eta(mpf(eta))) - 1))
    print(f"! max relative error on {len(grid)} points, eta in [1e-300, 1]: {worst:.3e}")
    for name, c in (("ellipk_fast_p", p), ("ellipk_fast_q", q)):
        print(f"real(dp), parameter :: {name}(0:{DEGREE}) = [ &")
        body = [f"   & {v!r}_dp" for v in c]
        print(", &\n".join(body) + "]")


if __name__ == "__main__":
    main()
