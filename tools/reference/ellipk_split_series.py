#!/usr/bin/env python3
"""Coefficients of egw_ellip's near-singular log split of K (ellipk_split_a, ellipk_split_b):

    K(k) = kreg + klog ln(1/kc),   kc = sqrt(1 - k**2),
    klog = sum_n b_n x**n,  kreg = sum_n 2 b_n (ln 2 - s_n) x**n,   x = kc**2,
    b_n = ((2n-1)!! / (2n)!!)**2,  s_n = sum_{j=1..n} 1/((2j-1) 2j)

(Abramowitz & Stegun 17.3.26 rearranged; the series ellipk_log_split sums term by term).
The half-space's product-integration pieces only see kc <= 1/3 (x <= 1/9), where the
series truncated after x**DEGREE is exact to far below an ulp; the arrays are printed for
ellip.f90, and the script checks the truncation and the double-precision evaluation
(Horner in double) against the full series in 50-digit decimal arithmetic on a grid of kc.
Standard library only (fractions, decimal).

Run from the repository root: python3 tools/reference/ellipk_split_series.py
"""
from decimal import Decimal, getcontext
from fractions import Fraction

DEGREE = 17
KC_MAX = Fraction(1, 3)


def coefficients(n_terms):
    """b_n and a_n = 2 b_n (ln 2 - s_n) as Decimals, n = 0 .. n_terms - 1."""
    ln2 = Decimal(2).ln()
    b, s = Fraction(1), Fraction(0)
    a_list, b_list = [], []
    for n in range(n_terms):
        if n > 0:
            b *= Fraction(2 * n - 1, 2 * n) ** 2
            s += Fraction(1, (2 * n - 1) * 2 * n)
        bd = Decimal(b.numerator) / Decimal(b.denominator)
        sd = Decimal(s.numerator) / Decimal(s.denominator)
        a_list.append(2 * bd * (ln2 - sd))
        b_list.append(bd)
    return a_list, b_list


def series(c, x):
    return sum(cn * x ** n for n, cn in enumerate(c))


def horner(c, x):
    acc = 0.0
    for v in reversed(c):
        acc = acc * x + v
    return acc


def main():
    getcontext().prec = 50
    a_full, b_full = coefficients(80)
    a_dp = [float(v) for v in a_full[:DEGREE + 1]]
    b_dp = [float(v) for v in b_full[:DEGREE + 1]]
    for name, c in (("ellipk_split_a", a_dp), ("ellipk_split_b", b_dp)):
        print(f"   real(dp), parameter :: {name}(0:{DEGREE}) = [ &")
        print(", &\n".join(f"      & {v!r}_dp" for v in c) + "]")
    worst_trunc, worst_dp = 0.0, 0.0
    for j in range(1, 2001):
        kc = Decimal(j) / Decimal(2000) * Decimal(KC_MAX.numerator) / KC_MAX.denominator
        x = kc * kc
        for full, trunc, c_dp in ((a_full, a_full[:DEGREE + 1], a_dp),
                                  (b_full, b_full[:DEGREE + 1], b_dp)):
            exact = series(full, x)
            worst_trunc = max(worst_trunc, float(abs(series(trunc, x) - exact) / exact))
            worst_dp = max(worst_dp, float(abs(Decimal(horner(c_dp, float(x))) - exact)
                                           / exact))
    print(f"! kc in (0, 1/3]: truncation after x**{DEGREE}: max relative {worst_trunc:.2e};"
          f" evaluated in double (Horner): max relative {worst_dp:.2e}")


if __name__ == "__main__":
    main()
