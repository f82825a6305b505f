#!/usr/bin/env python3
"""Stop 65 (psi31): the EP-GW unloading integral's calls, its panels and its accuracy.

  psi31_zu_panels.py hist PAIRS [SAMPLE]
      PAIRS: float64 (Delta, h_min) pairs of a build's unload_integral calls (captured as
      tools/bench/psi30_zu_replay.f90's header says), psi 1 law (K 0.6, rho_p 54). Prints
      where the contact edge z* = t* + h_min falls and the panels a call under
      egw_unloading's rule (a model of unload_integral's loop, same constants), without
      and with the tail grading (tail_width) at a few tail_grade values, on SAMPLE calls
      (default 40000, fixed seed).
  psi31_zu_panels.py compare A B [COLUMNS]
      A, B: float64 rows of tools/bench/psi31_zu_values.f90 (COLUMNS 2 for replay, 7 for
      sweep); prints the largest relative difference of Z_u and dZ_u/dh where A's Z_u is
      above 1e-30 (sweep) or 1e4 tiny (replay).
  psi31_zu_panels.py glerr
      The 16-point Gauss-Legendre rule's relative error on int_0^1 e^(-lambda x) dx and on
      the edge panel's int_0^1 3 v^2 e^(-lambda v^2) dv (mpmath, 40 digits), lambda 10..60:
      the ground of tail_grade.
Needs numpy (and mpmath for glerr): the project venv.
"""
import math
import sys

import numpy as np

PSI, K, RHO = 1.0, 0.6, 54.0
E = 1 / PSI ** 2
Q = RHO * E
C = math.sqrt(E) / K
LNQE = math.log(RHO)


def recovery(t):
    t = np.asarray(t, float)
    lam = (t - E) / (Q - E)
    area = 1 + lam * lam * (3 - 2 * lam)
    pres = 1 - (1 - K) * np.log(Q / t) / LNQE
    return np.where(t <= E, t, np.where(t <= Q, C * pres * np.sqrt(area * t),
                                        C * np.sqrt(2 * t)))


def contact_start(delta):
    """t* = D^-1(Delta), D = min(t, r(t)) (bisection; the law's Newton to the same root)."""
    t = np.empty_like(delta)
    r_q = C * math.sqrt(2 * Q)
    low = delta <= E
    high = delta > r_q
    mid = ~(low | high)
    t[low] = delta[low]
    t[high] = np.maximum(delta[high], 0.5 * (delta[high] / C) ** 2)
    lo = np.full(mid.sum(), E)
    hi = np.full(mid.sum(), Q)
    d = delta[mid]
    for _ in range(70):
        m = 0.5 * (lo + hi)
        below = np.minimum(m, recovery(m)) < d
        lo = np.where(below, m, lo)
        hi = np.where(below, hi, m)
    t[mid] = np.maximum(d, 0.5 * (lo + hi))
    return t


def switches():
    ts = np.exp(np.linspace(math.log(E * (1 + 1e-12)), math.log(Q), 100001))
    g = recovery(ts) - ts
    sw = list(ts[1:][np.sign(g[1:]) != np.sign(g[:-1])])
    if 2 * E / K ** 2 > Q:
        sw.append(2 * E / K ** 2)
    return sw


def panels(h_min, t_star, grade, sw):
    """unload_integral's panel loop (loss_max 36 + 6, max_width 2.5, dloss 10, ratio_max 2)."""
    z_star = t_star + h_min
    z_peak = max(z_star, 0.0)
    if z_peak > 38.7:
        return 0
    span = 42.0
    z_hi = z_peak + 2 * span / (z_peak + math.sqrt(z_peak * z_peak + 2 * span))
    z_lo = max(z_star, -math.sqrt(2 * span)) if z_peak > z_star else z_star
    breaks = sorted(b + h_min for b in [E, Q] + sw if z_lo < b + h_min < z_hi)
    z0, n = z_lo, 0
    for z1 in breaks + [z_hi]:
        if z1 <= z0:
            continue
        while z0 < z1:
            w = min(z1 - z0, 2.5)
            if abs(z0) > 1:
                w = min(w, 10 / abs(z0))
            t0 = max(z0 - h_min, t_star)
            if t0 >= E:
                w = min(w, 2 * t0)
            if z0 - z_star < w:
                if z0 > z_star:
                    w = min(w, 8 * (z0 - z_star))
            elif z0 > z_peak and grade > 0:
                g = 1 + grade * 0.5 * (z0 - z_peak) * (z0 + z_peak)
                wg = g * 2.5
                if abs(z0) > 1:
                    wg = min(wg, g * 10 / abs(z0))
                if t0 >= E:
                    wg = min(wg, 2 * t0)
                w = max(w, min(z1 - z0, wg, 2 * (z0 - z_star)))
            n += 1
            z0 += w
        z0 = max(z0, z1)
    return n


def hist(path, sample):
    pairs = np.fromfile(path).reshape(-1, 2)
    delta, h_min = pairs[:, 0], pairs[:, 1]
    t_star = contact_start(delta)
    z_star = t_star + h_min
    print(f"{len(delta)} calls, {len(np.unique(h_min))} distinct h_min")
    edges = [-40, -3, 0, 3, 6, 10, 20, 38.7, np.inf]
    for a, b in zip(edges[:-1], edges[1:]):
        print(f"  z* in [{a}, {b}): {np.mean((z_star >= a) & (z_star < b)):.3f}")
    sw = switches()
    pick = np.random.default_rng(2).choice(len(delta), min(sample, len(delta)), replace=False)
    for grade in (0.0, 0.1, 0.15, 0.2, 0.3):
        n = [panels(h_min[k], t_star[k], grade, sw) for k in pick]
        print(f"  tail_grade {grade}: {np.mean(n):.3f} panels a call")


def compare(a_path, b_path, columns):
    a = np.fromfile(a_path).reshape(-1, columns)
    b = np.fromfile(b_path).reshape(-1, columns)
    zc = columns - 2
    floor = 1e-30 if columns == 7 else 1e4 * np.finfo(float).tiny
    m = a[:, zc] > floor
    dz = np.abs(b[m, zc] - a[m, zc]) / a[m, zc]
    dd = np.abs(b[m, zc + 1] - a[m, zc + 1]) / np.abs(a[m, zc + 1])
    same = np.mean(np.all(a == b, axis=1))
    print(f"{m.sum()} rows compared: Z_u {dz.max():.2e}, dZ_u/dh {dd.max():.2e}; "
          f"bit-identical rows {same:.3f}")


def glerr():
    import mpmath as mp
    mp.mp.dps = 40
    x, w = np.polynomial.legendre.leggauss(16)
    nodes = [(1 + mp.mpf(float(t))) / 2 for t in x]
    weights = [mp.mpf(float(t)) / 2 for t in w]
    for lam in (10, 14, 20, 30, 40, 60):
        exact = (1 - mp.e ** (-lam)) / lam
        rule = sum(wi * mp.e ** (-lam * xi) for xi, wi in zip(nodes, weights))
        edge = mp.quad(lambda v: 3 * v * v * mp.e ** (-lam * v * v), [0, 1])
        edge_rule = sum(wi * 3 * xi * xi * mp.e ** (-lam * xi * xi)
                        for xi, wi in zip(nodes, weights))
        print(f"  lambda {lam}: exp {mp.nstr(abs(rule - exact) / exact, 3)}, "
              f"edge {mp.nstr(abs(edge_rule - edge) / edge, 3)}")


if __name__ == "__main__":
    if sys.argv[1] == "hist":
        hist(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 40000)
    elif sys.argv[1] == "compare":
        compare(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 2)
    else:
        glerr()
