#!/usr/bin/env python3
"""Hertz + cap contact duration from tools/reference/cap_reference.py's forces (stop 61).

The duration (doc/theory.md section 10: the time the force spends above 1 % of its peak P_m,
loading and unloading) of the smooth sphere with the flow-pressure cap, from the independent
cap solver of cap_reference.py (its rings, not egw's; forces ~2e-5 accurate) instead of
egw's own forces (duration_reference.py): a check of egw_time_step at the forces' level.

Universal units (cap_reference.py): Delta in delta_y, P in P_y = (4/3) E* sqrt(R) delta_y**1.5,
works in P_y delta_y, W_load = 2/5 (v/v_y)**2. With v(Delta)**2 = (2/m*) W_left(Delta) P_y
delta_y the time is T0 int dDelta/sqrt(W_left), T0 = delta_y/sqrt(2 P_y delta_y/m*).
- Loading: Hertz (P = Delta**1.5, W = 0.4 Delta**2.5) from the onset Delta_1 = (P_m/100)**(2/3)
  to first yield Delta = 1 (scipy quad), then the capped branch parametrised by the cap radius
  c in [0, c_m] (Chebyshev fits of Delta(c), P(c), degree 40, as cap_reference's works),
  c = c_m - s**2 (the turning point's 1/sqrt becomes regular), Gauss-Legendre in s.
- Unloading from c_m: the pinned phase (contact radius a: P linear in Delta, its time
  by quad after x = y**2), then the contact radius b from a down to the onset b_1
  (P(b_1) = P_m/100) on the pieces [b_1, c] and [c, a] (fits of Delta(b), P(b), degree 24),
  b = a - s**2 on the outer piece.
Each at m = 20, 40, 80 ring elements; the differences are printed (the reference's error).

    PYTHONPATH=<numpy, scipy> python tools/reference/cap_duration_reference.py

Output (stop 61): m = 20, 40, 80: 5.937014135448e-06, 5.937010709579e-06,
5.937010291319e-06 s (the loading work of the fits within 1.3e-8 of m* v**2/2 at m = 80).
"""
import math
import os
import sys

import numpy as np
from numpy.polynomial import chebyshev as C
from scipy.integrate import quad
from scipy.optimize import brentq

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cap_reference as cr  # noqa: E402

# test_cap_hysteresis "contact duration: cap and rough models", case 1 (Hertz + cap)
RADIUS, MODULUS, MASS, P_Y, VELOCITY = 5e-4, 4e10, 6.5e-6, 1e9, 1.0
XL, WL = np.polynomial.legendre.leggauss(200)


def gauss(f, lo, hi):
    x = lo + (hi - lo) * 0.5 * (XL + 1)
    return 0.5 * (hi - lo) * np.sum(WL * f(x))


def fit(fun, lo, hi, deg):
    x = C.chebpts2(deg + 1)
    vals = np.array([fun(lo + (hi - lo) * 0.5 * (t + 1)) for t in x])
    return [C.chebfit(x, vals[:, k], deg) for k in range(2)]


def loading_time(w_m, m):
    """Loading half (T0 units), c_m and P_m for the loading work w_m."""
    c_big = cr.load_at_delta(4 * (w_m / 0.4)**0.4, m)[0]
    dc, pc = fit(lambda c: cr.load_at_c(c, m)[:2] if c > 0 else (1.0, 1.0), 0.0, c_big, 40)
    def work(cd, cp, c, c_hi):
        ci = C.chebint(C.chebmul(cp, C.chebder(cd)))
        return 0.4 + C.chebval(2 * c / c_hi - 1, ci) - C.chebval(-1, ci)
    c_m = brentq(lambda c: work(dc, pc, c, c_big) - w_m, 1e-9, c_big, xtol=1e-15)
    dc, pc = fit(lambda c: cr.load_at_c(c, m)[:2] if c > 0 else (1.0, 1.0), 0.0, c_m, 40)
    ci = C.chebint(C.chebmul(pc, C.chebder(dc)))   # int P dDelta (x = 2c/c_m - 1)
    p_m = C.chebval(1.0, pc)
    w_top = 0.4 + C.chebval(1.0, ci) - C.chebval(-1.0, ci)

    def integrand(s):
        c = c_m - s**2
        x = 2 * c / c_m - 1
        left = C.chebval(1.0, ci) - C.chebval(x, ci)    # W(c_m) - W(c)
        return 2 * s * C.chebval(x, C.chebder(dc)) * 2 / c_m / np.sqrt(left)
    capped = gauss(integrand, 0.0, math.sqrt(c_m))
    d_1 = (0.01 * p_m)**(2 / 3)
    assert d_1 < 1, "the onset lies beyond first yield"
    hertz, _ = quad(lambda d: 1 / math.sqrt(w_top - 0.4 * d**2.5), d_1, 1.0, epsabs=0,
                    epsrel=1e-13, limit=200)
    return hertz + capped, c_m, p_m, w_top


def unloading_time(c_m, p_m, m):
    ld = cr.Loaded(c_m, m)
    d_a, p_a = ld.unload(ld.a)
    x_a = max(0.0, ld.dm - d_a)
    k = (ld.pm - p_a) / x_a if x_a > 0 else 0.0
    pinned, _ = quad(lambda y: 2 / math.sqrt(ld.pm - 0.5 * k * y * y), 0.0, math.sqrt(x_a),
                     epsabs=0, epsrel=1e-13) if x_a > 0 else (0.0, None)
    w_1 = ld.pm * x_a - 0.5 * k * x_a**2
    target = 0.01 * p_m
    b_1 = brentq(lambda b: ld.unload(b)[1] - target, 1e-6 * ld.a, ld.c, xtol=1e-15, rtol=1e-15)
    total = pinned
    w_hi = w_1
    # outer piece [c, a] in s (b = a - s**2), then the inner [b_1, c]
    s_c = math.sqrt(ld.a - ld.c)
    ds_, ps_ = fit(lambda s: ld.unload(ld.a - s * s), 0.0, s_c, 24)
    ci = C.chebint(C.chebmul(ps_, C.chebder(ds_)))    # int P dDelta along s (< 0)

    def outer(s):
        x = 2 * s / s_c - 1
        w = w_1 - (C.chebval(x, ci) - C.chebval(-1.0, ci))
        return -C.chebval(x, C.chebder(ds_)) * 2 / s_c / np.sqrt(w)
    total += gauss(outer, 0.0, s_c)
    w_hi = w_1 - (C.chebval(1.0, ci) - C.chebval(-1.0, ci))
    db, pb = fit(lambda b: ld.unload(b), b_1, ld.c, 24)
    cb = C.chebint(C.chebmul(pb, C.chebder(db)))

    def inner(b):
        x = 2 * (b - b_1) / (ld.c - b_1) - 1
        w = w_hi + (C.chebval(1.0, cb) - C.chebval(x, cb))
        return C.chebval(x, C.chebder(db)) * 2 / (ld.c - b_1) / np.sqrt(w)
    total += gauss(inner, b_1, ld.c)
    return total


def main():
    delta_y = (math.pi * P_Y / (2 * MODULUS))**2 * RADIUS
    force_y = 4 / 3 * MODULUS * math.sqrt(RADIUS) * delta_y**1.5
    w_m = 0.5 * MASS * VELOCITY**2 / (force_y * delta_y)
    t0 = delta_y / math.sqrt(2 * force_y * delta_y / MASS)
    print(f"Hertz + cap: v/v_y = {math.sqrt(w_m / 0.4):.6f}, delta_y = {delta_y:.6e}")
    for m in (20, 40, 80):
        t_load, c_m, p_m, w_top = loading_time(w_m, m)
        t_unload = unloading_time(c_m, p_m, m)
        print(f"m = {m}: duration {t0 * (t_load + t_unload):.12e} (loading {t0 * t_load:.12e}, "
              f"unloading {t0 * t_unload:.12e}; W_top/W_m - 1 = {w_top / w_m - 1:+.1e})",
              flush=True)


if __name__ == "__main__":
    main()
