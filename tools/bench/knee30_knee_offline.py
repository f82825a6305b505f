#!/usr/bin/env python3
"""Which knee lines up a rough + cap table's curves in s across delta_max (doc/benchmarks.md
"Stop 64: knee30"): unloading curves solved at a few turning points near the rough first
yield, their features, and the four-point Lagrange mismatch in delta_max at a midpoint
under candidate knees (the two-piece map of src/egw/tables/hysteresis_data.f90, map_s /
map_x, and a three-break map with the kink too), offline: no table is built.

usage: knee30_knee_offline.py TABLE.bin [--rel-tol R] [--dir D] [--more M ...]

TABLE.bin: README's E-GW + cap table (egw-table ... --model E-GW --flow-pressure 0.01
--out DIR, DIR/scene_hysteresis.bin; its .csv beside it): its loading table gives
P_load, its knees (the smooth cap's delta_r at its nodes, cubic spline between) the
main knee, its header the parameters and tail_length. Curves: egw.solve_unload at
rel_tol R (1e-5, the tables' own) from m down to 40 sigma at 40 overlaps, then every
0.25 sigma to -6 sigma (cached as D/c_<m>.npy). g = (P_load(delta) - P)/P_load(m), in
units of P(m) as the build's check. Between a node's samples g is PCHIP-interpolated in
delta (its own error, half-grid test: <= 1.2e-5 of P(m)). --more: features only, at
further turning points (40 overlaps from m to m/2, 200 from there to -6 sigma).
"""
import argparse
import os
import numpy as np
import egw
from scipy.interpolate import CubicSpline, PchipInterpolator

S_KNEE, S_ZERO = 0.5, 0.75
# the turning points: README's main grid nodes and midpoints near first yield (sigma)
MS = [98.308, 100.268, 102.228, 104.187, 106.147, 108.107, 110.067, 113.986, 117.906,
      121.825, 125.745, 129.664, 133.583, 137.503, 141.42, 145.342]
# (stencil, midpoints): 7.84 sigma spacing, 3.92 (main's final grid there), 15.7
TESTS = [([98.308, 106.147, 113.986, 121.825], [102.228, 110.067, 117.906]),
         ([106.147, 113.986, 121.825, 129.664], [117.906]),
         ([113.986, 121.825, 129.664, 137.503], [125.745]),
         ([121.825, 129.664, 137.503, 145.342], [133.583]),
         ([98.308, 102.228, 106.147, 110.067], [100.268, 104.187, 108.107]),
         ([98.308, 113.986, 129.664, 145.342], [106.147, 121.825, 137.503])]


def header(path_bin):
    h = {}
    for line in open(path_bin[:-4] + ".csv"):
        if line.startswith("# ") and " = " in line:
            k, v = line[2:].split(" = ", 1)
            h.setdefault(k.strip(), []).append(v.strip())
    return h


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("table")
    ap.add_argument("--rel-tol", type=float, default=1e-5)
    ap.add_argument("--dir", default=".")
    ap.add_argument("--more", type=float, nargs="*", default=[])
    args = ap.parse_args()
    h = header(args.table)
    t = egw.HysteresisTable.read(args.table)
    tail = float(h["tail_length"][0])
    params = egw.Params(model="E-GW", radius=float(h["radius"][0]),
                        modulus=float(h["modulus"][0]), sigma=float(h["sigma"][0]),
                        mu=float(h["mu"][0]), flow_pressure=float(h["flow_pressure"][0]))
    delta_y = 100.0 * float(h["sigma"][0])   # README's scene: delta_y = 100 sigma
    knees = np.array([float(v) for v in h["knee"]])
    nodes = np.unique([float(l.split(",")[0]) for l in open(args.table[:-4] + ".csv")
                       if l[:1].isdigit()])
    spline = CubicSpline(nodes, knees)

    def smooth(m):   # the main knee: delta_r(m), 0 up to delta_y
        return 0.0 if m <= delta_y else max(float(spline(m)), 0.0)

    def pload(d):
        return np.array([float(t.eval(float(x), egw.HysteresisTable.new_state(()))[0])
                         for x in np.atleast_1d(d)])

    opts = egw.Options(rel_tol=args.rel_tol)
    curves = {}
    for m in MS + args.more:
        f = os.path.join(args.dir, f"c_{m:.3f}.npy")
        if not os.path.exists(f):
            ds = np.concatenate([np.linspace(m, 40, 40, endpoint=False),
                                 np.arange(40, -6.01, -0.25)])
            if m in args.more:
                ds = np.concatenate([np.linspace(m, m / 2, 40, endpoint=False),
                                     np.linspace(m / 2, -6, 200)])
            p = np.array([egw.solve_unload(params, float(d), float(m), opts).force
                          for d in ds])
            np.save(f, np.vstack([ds, p]))
        ds, p = np.load(f)
        d, p = ds[::-1], p[::-1]
        pl = pload(d)
        curves[m] = (d, (pl - p) / pload(m)[0], p / pl)

    def edge(m, q):   # where P/P_load first exceeds q (the rough edge; 0 if it never falls)
        d, g, r = curves[m]
        if r.min() > q:
            return 0.0
        i = np.where(r > q)[0][0]
        return d[i - 1] + (q - r[i - 1]) * (d[i] - d[i - 1]) / (r[i] - r[i - 1])

    def gpeak(m):   # the local maximum of g above the knee (the annulus kink's trace)
        d, g, r = curves[m]
        sel = (d > smooth(m) + 0.5) & (d < m - 0.5 * delta_y)
        return d[np.argmax(np.where(sel, g, -1))] if sel.any() else 0.0

    print("features (sigma): m, delta_r (main knee), P/P_load = 0.01, 0.5, 0.9 crossings, "
          "g's peak")
    for m in MS + args.more:
        print(f"  {m:8.3f} {smooth(m):7.3f} {edge(m, 0.01):8.3f} {edge(m, 0.5):8.3f} "
              f"{edge(m, 0.9):8.3f} {gpeak(m):7.2f}")

    def lag(x, xm):
        w = np.ones(len(xm))
        for k in range(len(xm)):
            for l in range(len(xm)):
                if l != k:
                    w[k] *= (x - xm[l]) / (xm[k] - xm[l])
        return w

    def breaks_x(m, b, s):   # x = m - delta at s; b: [(s_break, delta_break)] above 0
        pts = [(0.0, m)] + b + [(S_ZERO, 0.0)]
        if s > S_ZERO:
            return m + tail * (s - S_ZERO) / (1 - S_ZERO)
        for (s0, d0), (s1, d1) in zip(pts, pts[1:]):
            if s <= s1:
                return m - (d0 + (d1 - d0) * (s - s0) / (s1 - s0) if s1 > s0 else d1)
        return m

    def breaks_s(m, b, x):
        pts = [(0.0, m)] + b + [(S_ZERO, 0.0)]
        d = m - x
        if d < 0:
            return S_ZERO + (1 - S_ZERO) * (-d) / tail
        for (s0, d0), (s1, d1) in zip(pts, pts[1:]):
            if d >= d1:
                return s0 + (s1 - s0) * (d0 - d) / (d0 - d1) if d0 > d1 else s1
        return S_ZERO

    def mismatch(stencil, mid, knees_of):   # knees_of(m) -> [(s_break, delta_break)]
        w = lag(mid, stencil)
        kb = [knees_of(n) for n in stencil]
        bm = [(kb[0][i][0], min(max(sum(w[k] * kb[k][i][1] for k in range(4)), 0.0),
                                0.99 * mid)) for i in range(len(kb[0]))]
        for i in range(1, len(bm)):   # (breaks decreasing in delta)
            bm[i] = (bm[i][0], min(bm[i][1], bm[i - 1][1]))
        gf = [PchipInterpolator(curves[n][0], curves[n][1]) for n in stencil]
        d, g, r = curves[mid]
        worst = (0.0, 0.0)
        for di, gi in zip(d, g):
            if di > mid or di < -6:
                continue
            s = min(breaks_s(mid, bm, mid - di), 1.0)
            v = sum(w[k] * float(gf[k](n - breaks_x(n, kb[k], s)))
                    for k, n in enumerate(stencil))
            if abs(v - gi) > worst[0]:
                worst = (abs(v - gi), s)
        return worst

    def clamp(m, k):
        return min(max(k, 0.0), 0.99 * m)

    cands = {"main: delta_r": lambda m: [(S_KNEE, smooth(m))]}
    for c in (1.5, 2.0, 3.0):
        cands[f"{c} delta_r"] = (lambda c: lambda m: [(S_KNEE, clamp(m, c * smooth(m)))])(c)
    for q in (0.01, 0.5):
        cands[f"edge P/P_load={q}"] = (lambda q: lambda m: [(S_KNEE, clamp(m, edge(m, q)))])(q)
    cands["g's peak"] = lambda m: [(S_KNEE, clamp(m, gpeak(m)))]
    cands["m - delta_y"] = lambda m: [(S_KNEE, clamp(m, m - delta_y))]
    cands["3 breaks: m - delta_y, delta_r"] = lambda m: [
        (S_KNEE, clamp(m, max(m - delta_y, smooth(m)))), (0.625, smooth(m))]
    print("largest |g_stencil - g_mid|/1e-4 of P(m) at the midpoint (at s); stencils:",
          "; ".join(f"{s[0]:.0f}..{s[3]:.0f}" for s, _ in TESTS))
    for name, k in cands.items():
        out = []
        for stencil, mids in TESTS:
            for mid in mids:
                e, s = mismatch(stencil, mid, k)
                out.append(f"{mid:.0f}:{e * 1e4:5.2f}@{s:.2f}")
        print(f"  {name:32s} " + " ".join(out), flush=True)


if __name__ == "__main__":
    main()
