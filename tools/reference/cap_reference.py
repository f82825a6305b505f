#!/usr/bin/env python3
"""Independent reference for the flow-pressure cap of a smooth sphere (doc/theory.md §12).

Model (universal units, as in issue 32): delta in delta_y = (pi p_y/(2E*))^2 R, radii in
a_y = sqrt(R delta_y), pressure in p_y, force in P_y = (4/3) E* sqrt(R) delta_y^1.5. Gap
g(rho) = f(rho) - Delta + w(rho), w = (2/pi^2) int p(t) g_ring(rho, t) dt. Loading: f = rho^2/2,
0 <= p <= 1 (the cap), g >= 0 where p = 0, g = 0 where 0 < p < 1, g <= 0 where p = 1. The plastic
displacement at Delta_m is u_pl = -g on the capped disk; unloading is elastic (no cap) with
f = rho^2/2 + u_pl.

Method (independent of egw's rings with constant pressure, midpoint collocation and box LCP):
- Loading is parametrised by the cap radius c: p = 1 on [0, c] (closed-form disk displacement
  with complete elliptic integrals), a continuous piecewise-linear pressure on [c, a] on a
  Chebyshev-Lobatto mesh (clustered at both ends), p(c) = 1, p(a) = 0, gap = 0 collocated at all
  ring nodes. Unknowns: the interior pressures and Delta; the one surplus equation fixes the
  contact radius a (a 1-D root). No active set at all: the edges are mesh nodes.
- The displacement of a piecewise-linear pressure is -(2/pi^2) sum_e slope_e int_e D(rho; t) dt
  where D(rho; t) is the exact displacement of a unit-pressure disk of radius t (elliptic K, E);
  the element integrals use Gauss-Legendre after a smoothstep map (the log kink at t = rho sits
  at element ends).
- Unloading is parametrised by its contact radius b: nodes rho_i = b sin(pi i/(2m)), p(b) = 0,
  gap = 0 at every node: a linear system for the pressures and Delta.
- Works: W_load = 2/5 + int P dDelta and W_unload = int P dDelta, both as int P(s) Delta'(s) ds
  over the parameter (c or b) with piecewise Chebyshev fits; e^2 = W_unload/W_load,
  (v/v_y)^2 = W_load/(2/5).
- Every quantity at m, 2m, 4m ring elements; Richardson extrapolation with the observed order
  (about 3 on loading, 2 on unloading); the error column is |extrapolated - finest| (the
  finest level's error, a bound on the extrapolated value's), or |finest - middle| when the
  differences do not decrease monotonically.

Run: python tools/reference/cap_reference.py [--m 40] [--out test/data/cap_reference.csv]
     python tools/reference/cap_reference.py --profile 2 5 20 (loading p(rho), w(rho))
     python tools/reference/cap_reference.py --profile-unload 10 0.99 0.9 0.8 (unloading p)
"""
import argparse
import os
import sys

import numpy as np
from numpy.polynomial import chebyshev as C
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

PI = np.pi
NQ = 24
XG, WG = np.polynomial.legendre.leggauss(NQ)
SG = 0.5 * (XG + 1.0)
# smoothstep t = 3s^2 - 2s^3, dt/ds = 6s(1-s)
TS = 3 * SG**2 - 2 * SG**3
WS = 0.5 * WG * 6 * SG * (1 - SG)


def disk(rho, t):
    """Integral of dA/|x - x'| over a disk of radius t at radius rho (unit pressure)."""
    rho, t = np.broadcast_arrays(np.asarray(rho, float), np.asarray(t, float))
    out = np.empty(rho.shape)
    inside = rho <= t
    with np.errstate(divide="ignore", invalid="ignore"):
        m1 = np.where(inside, (rho / np.where(t > 0, t, 1)) ** 2, 0.0)
        out[inside] = 4 * t[inside] * ellipe(m1[inside])
        o = ~inside
        m2 = (t[o] / rho[o]) ** 2
        out[o] = 4 * rho[o] * (ellipe(m2) - (1 - m2) * ellipk(m2))
    return out


def elem_int(rho, t0, t1):
    """I[i, e] = int_{t0_e}^{t1_e} D(rho_i; t) dt (rho must not lie inside an element)."""
    rho = np.asarray(rho, float)[:, None, None]
    h = (t1 - t0)[None, :, None]
    t = t0[None, :, None] + h * TS[None, None, :]
    return np.sum(disk(rho, t) * WS[None, None, :], axis=2) * h[:, :, 0]


def w_linear(rho, nodes, p):
    """Displacement at rho of the continuous piecewise-linear p on nodes (p(end) = 0)."""
    h = np.diff(nodes)
    slope = np.diff(p) / h
    return -(2 / PI**2) * elem_int(rho, nodes[:-1], nodes[1:]) @ slope


def force_linear(nodes, p):
    """3 int rho p drho over the piecewise-linear part (exact)."""
    t0, t1, p0, p1 = nodes[:-1], nodes[1:], p[:-1], p[1:]
    # int t (p0 + (p1-p0)(t-t0)/h) dt
    h = t1 - t0
    return 3 * np.sum(h * (p0 * (t0 / 2 + h / 6) + p1 * (t0 / 2 + h / 3)))


def _force_linear_check():
    n = np.array([0.0, 1.0])
    # p = 1 - t on [0, 1]: int t (1 - t) = 1/6 -> 0.5
    assert abs(force_linear(n, np.array([1.0, 0.0])) - 0.5) < 1e-14


def ring_matrix(nodes):
    """A[i, j]: w(node_i) per unit p_j (piecewise-linear hats on nodes)."""
    h = np.diff(nodes)
    ii = elem_int(nodes, nodes[:-1], nodes[1:]) / h[None, :]
    a = np.zeros((len(nodes), len(nodes)))
    a[:, :-1] += ii   # slope_e = (p_{e+1} - p_e)/h_e: -I_e/h_e on p_e
    a[:, 1:] -= ii
    return -(2 / PI**2) * (-a)


def load_state(c, a, m):
    """Solve the ring [c, a] for given (c, a): returns residual at a, Delta, P, nodes, p."""
    s = 0.5 * (1 - np.cos(PI * np.arange(m + 1) / m))
    nodes = c + (a - c) * s
    A = ring_matrix(nodes)
    # p = 1 on [0, c] has zero slope: w = -(2/pi^2) sum_e slope_e I_e over the ring alone
    # unknowns x = (p_1..p_{m-1}, Delta); equations gap(node_i) = 0, i = 0..m-1
    M = np.zeros((m + 1, m))
    M[:, : m - 1] = A[:, 1:m]
    M[:, m - 1] = -1.0
    rhs = -(0.5 * nodes**2 + A[:, 0] * 1.0)
    x = np.linalg.solve(M[:m], rhs[:m])
    resid = M[m] @ x - rhs[m]
    p = np.concatenate([[1.0], x[: m - 1], [0.0]])
    delta = x[m - 1]
    force = 1.5 * c**2 + force_linear(nodes, p)
    return resid, delta, force, nodes, p


def load_at_c(c, m):
    """Contact radius a(c) from the surplus equation; returns (Delta, P, a, nodes, p).

    Once the elastic ring is thinner than 1e-9 c (from ~20 delta_y: its width falls
    exponentially with a) the contact is fully capped: p = 1 on [0, a], a = c, gap(a) = 0
    with the disk's edge displacement 8a/pi^2; nodes, p are then None."""
    f = lambda a: load_state(c, a, m)[0]
    lo = c * (1 + 1e-9)
    flo = f(lo)
    for hi in c + np.geomspace(1e-8 * c, 2.0 * max(c, 1.0), 80):
        fhi = f(hi)
        if np.sign(fhi) != np.sign(flo):
            break
        lo, flo = hi, fhi
    else:
        return c**2 / 2 + 8 * c / PI**2, 1.5 * c**2, c, None, None
    a = brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
    _, delta, force, nodes, p = load_state(c, a, m)
    return delta, force, a, nodes, p


def load_at_delta(delta, m):
    """Loading solve at Delta > 1 by a root in c."""
    g = lambda c: load_at_c(c, m)[0] - delta
    hi = -8 / PI**2 + np.sqrt(64 / PI**4 + 2 * delta)   # the fully capped radius
    lo = 1e-4
    c = brentq(g, lo, hi, xtol=1e-14, rtol=1e-15)
    return (c,) + load_at_c(c, m)


def unload_state(b, f_of_rho, m, c=None, nodes_too=False):
    """Unloading with contact radius b: (Delta, P). Nodes b sin(pi i/(2m)); when b > c
    (the loading's cap radius, where f has its steep shoulder), sine nodes on [0, c] and
    Chebyshev-Lobatto nodes on [c, b]."""
    if c is None or b <= c * (1 + 1e-12):
        nodes = b * np.sin(0.5 * PI * np.arange(m + 1) / m)
    else:
        inner = c * np.sin(0.5 * PI * np.arange(m + 1) / m)
        outer = c + (b - c) * 0.5 * (1 - np.cos(PI * np.arange(1, m // 2 + 1) / (m // 2)))
        nodes = np.concatenate([inner, outer])
        m = len(nodes) - 1
    A = ring_matrix(nodes)
    # unknowns p_0..p_{m-1}, Delta; equations f + w - Delta = 0 at all nodes
    M = np.zeros((m + 1, m + 1))
    M[:, :m] = A[:, :m]
    M[:, m] = -1.0
    x = np.linalg.solve(M, -f_of_rho(nodes))
    p = np.concatenate([x[:m], [0.0]])
    if nodes_too:
        return x[m], force_linear(nodes, p), p, nodes
    return x[m], force_linear(nodes, p), p


class Loaded:
    """A loading to Delta_m (given by its cap radius) and its unloading."""

    def __init__(self, c, m):
        self.m = m
        self.c = c
        self.dm, self.pm, self.a, self.nodes, self.p = load_at_c(c, m)

    def w(self, rho):
        rho = np.asarray(rho, float)
        if self.nodes is None:
            return (2 / PI**2) * disk(rho, np.full(rho.shape, self.c))
        return w_linear(rho, self.nodes, self.p)

    def f(self, rho):
        rho = np.asarray(rho, float)
        u = np.zeros(rho.shape)
        ins = rho < self.c
        if ins.any():
            u[ins] = np.maximum(0.0, self.dm - 0.5 * rho[ins] ** 2 - self.w(rho[ins]))
        return 0.5 * rho**2 + u

    def residual(self):
        rho = np.linspace(0, self.c, 401)
        return float(np.min(self.f(rho)))

    def unload(self, b):
        d, P, _ = unload_state(b, self.f, self.m, self.c)
        return d, P

    def unload_at(self, delta):
        g = lambda b: self.unload(b)[0] - delta
        b = brentq(g, 1e-6 * self.a, self.a, xtol=1e-15, rtol=1e-15)
        return self.unload(b)[1]

    def unload_work(self, deg=24):
        """int P dDelta over the unloading, piecewise Chebyshev in b on [0, c], [c, a].

        Plus the first phase, where the contact edge stays pinned at b = a (the fully
        capped contact's deformed shape has a log-steep shoulder there) while Delta falls
        from Delta_m to Delta(b = a): at a fixed contact radius the problem is linear, P is
        linear in Delta, and its work is the trapezoid (P_m + P(a))(Delta_m - Delta(a))/2
        exactly. (Without it e at 100 v_y converged at order 1, to 3.5e-3 only.)"""
        d_a, p_a = self.unload(self.a)
        total = 0.5 * (self.pm + p_a) * max(0.0, self.dm - d_a)
        for lo, hi in ((1e-9 * self.a, self.c), (self.c, self.a)):
            if hi - lo < 1e-12 * self.a:
                continue
            x = C.chebpts2(deg + 1)
            b = lo + (hi - lo) * 0.5 * (x + 1)
            vals = np.array([self.unload(bb) for bb in b])
            cd = C.chebfit(x, vals[:, 0], deg)
            cp = C.chebfit(x, vals[:, 1], deg)
            integrand = C.chebmul(cp, C.chebder(cd))
            ci = C.chebint(integrand)
            total += C.chebval(1, ci) - C.chebval(-1, ci)
        return total


def load_curve(m, c_max, deg=40):
    """Chebyshev fits of Delta(c), P(c) on [0, c_max] (c = 0 is first yield)."""
    x = C.chebpts2(deg + 1)
    cs = 0.5 * c_max * (x + 1)
    vals = []
    for c in cs:
        if c == 0:
            vals.append((1.0, 1.0))
        else:
            d, P, *_ = load_at_c(c, m)
            vals.append((d, P))
    vals = np.array(vals)
    return C.chebfit(x, vals[:, 0], deg), C.chebfit(x, vals[:, 1], deg), c_max


def load_work(curve, c):
    cd, cp, c_max = curve
    x = 2 * c / c_max - 1
    ci = C.chebint(C.chebmul(cp, C.chebder(cd)))
    return 0.4 + C.chebval(x, ci) - C.chebval(-1, ci)


def richardson(q):
    """q at m, 2m, 4m -> (extrapolated, error estimate, observed order)."""
    q1, q2, q3 = q
    d1, d2 = q2 - q1, q3 - q2
    if d1 != 0 and d2 != 0 and d2 / d1 > 0 and abs(d2 / d1) < 0.9:
        order = np.log2(d1 / d2)
        ext = q3 + d2 / (2**order - 1)
    else:
        order = float("nan")
        ext = q3
    err = abs(ext - q3) if order == order else abs(d2)
    return ext, err, order


def profile(delta, ms):
    """Loading profile at Delta: p(rho) [p_y] and w(rho) [delta_y] at rho = 0.5 c, c + f (a -
    c) for f = 0.1 ... 0.9 and 1.1 a, 1.5 a (c, a of the finest level), each at m, 2m, 4m
    rings (p piecewise linear between the ring nodes, exactly the discrete solution; w on
    [0, a] is Delta - rho^2/2, beyond a the rings' w_linear) and Richardson-extrapolated.
    Prints one line per radius: rho p p_err w w_err."""
    sols = [load_at_delta(delta, m) for m in ms]
    c, _, _, a, _, _ = sols[-1]
    rhos = [0.5 * c] + [c + f * (a - c) for f in (0.1, 0.3, 0.5, 0.7, 0.9)] + [1.1 * a, 1.5 * a]
    print(f"# Delta = {delta}: c = {c!r}, a = {a!r}")
    for rho in rhos:
        ps, ws = [], []
        for cc, dd, _, aa, nodes, p in sols:
            if nodes is None:
                ps.append(1.0 if rho <= aa else 0.0)
                ws.append(dd - 0.5 * rho**2 if rho <= aa else
                          (2 / PI**2) * disk(np.array([rho]), np.array([aa]))[0])
                continue
            ps.append(1.0 if rho <= cc else float(np.interp(rho, nodes, p, right=0.0)))
            ws.append(dd - 0.5 * rho**2 if rho <= aa else float(w_linear([rho], nodes, p)[0]))
        pe, perr, _ = richardson(ps)
        we, werr, _ = richardson(ws)
        print(f"{rho!r} {pe!r} {perr:.2e} {we!r} {werr:.2e}")


def profile_unload(dm, fracs, ms):
    """Unloading pressure after loading to Delta_m, at Delta = frac Delta_m: p(rho) [p_y] at
    rho = (0, 0.3, 0.6, 0.8, 0.9, 0.97) b (b the finest level's contact radius), p piecewise
    linear between the unloading nodes, at m, 2m, 4m and Richardson-extrapolated. Prints
    rho p p_err per radius."""
    lds = [Loaded(load_at_delta(dm, m)[0], m) for m in ms]
    for frac in fracs:
        d = frac * dm
        sols = []
        for ld in lds:
            b = brentq(lambda bb: ld.unload(bb)[0] - d, 1e-6 * ld.a, ld.a, xtol=1e-15,
                       rtol=1e-15)
            _, force, p, nodes = unload_state(b, ld.f, ld.m, ld.c, nodes_too=True)
            sols.append((b, force, p, nodes))
        b = sols[-1][0]
        fe, ferr, _ = richardson([s_[1] for s_ in sols])
        print(f"# Delta_m = {dm}, Delta = {d!r}: b = {b!r}, P = {fe!r} +- {ferr:.1e}")
        for x in (0.0, 0.3, 0.6, 0.8, 0.9, 0.97):
            rho = x * b
            ps = [float(np.interp(rho, nodes, p, right=0.0)) for _, _, p, nodes in sols]
            pe, perr, _ = richardson(ps)
            print(f"{rho!r} {pe!r} {perr:.2e}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--m", type=int, default=40)
    ap.add_argument("--out", default="test/data/cap_reference.csv")
    ap.add_argument("--profile", type=float, nargs="*",
                    help="print the loading profile at these Delta (see profile) and stop")
    ap.add_argument("--profile-unload", type=float, nargs="*",
                    help="DELTA_M FRAC...: print the unloading pressure at Delta = FRAC "
                    "Delta_m (see profile_unload) and stop")
    args = ap.parse_args()
    if args.profile_unload:
        profile_unload(args.profile_unload[0], args.profile_unload[1:],
                       [args.m, 2 * args.m, 4 * args.m])
        return
    if args.profile:
        for d in args.profile:
            profile(d, [args.m, 2 * args.m, 4 * args.m])
        return
    _force_linear_check()
    ms = [args.m, 2 * args.m, 4 * args.m]
    # self-checks: Hertz (f = rho^2/2, b = 1.3: Delta = b^2, P = b^3) and first yield
    # (c -> 0: Delta -> 1, P -> 1)
    hz = [unload_state(1.3, lambda r: 0.5 * r**2, m)[:2] for m in ms]
    for k, exact in ((0, 1.69), (1, 1.3**3)):
        ext, err, order = richardson([h[k] for h in hz])
        print("hertz", k, ext - exact, err, order, file=sys.stderr)
        assert abs(ext - exact) < 1e-6 * exact and err < 1e-4 * exact
    fy = [load_at_c(1e-3, m)[:2] for m in ms]
    print("first yield (c = 1e-3)", fy, file=sys.stderr)
    assert abs(fy[-1][0] - 1) < 1e-5 and abs(fy[-1][1] - 1) < 1e-5
    rows = []

    # loading curve and unloading at fixed Delta
    for d in [1.0, 1.5, 2, 3, 5, 10, 20, 50, 100]:
        if d == 1.0:
            rows.append(("load", d, 1.0, 1.0, 0.0, 0.0, "hertz exact"))
            continue
        q = [load_at_delta(d, m)[2] for m in ms]
        ext, err, order = richardson(q)
        rows.append(("load", d, 0.0, ext, err, order, ""))
        print("load", d, q, ext, err, order, file=sys.stderr)

    for dm in [2.0, 10.0, 20.0, 50.0, 100.0]:
        lds = []
        for m in ms:
            c = load_at_delta(dm, m)[0]
            lds.append(Loaded(c, m))
        res = [ld.residual() / dm for ld in lds]
        ext, err, order = richardson(res)
        rows.append(("residual", dm, 0.0, ext, err, order, "delta_r/delta_max"))
        print("residual", dm, res, ext, err, file=sys.stderr)
        for r in [0.999, 0.99, 0.98, 0.95, 0.9, 0.8]:
            dd = r * dm
            if dd <= max(ld.residual() for ld in lds) * 1.001:
                continue
            if any(dd >= ld.unload(ld.a)[0] for ld in lds):
                print("unload", dm, r, "beyond the discrete Delta(b = a): skipped",
                      file=sys.stderr)
                continue
            q = [ld.unload_at(dd) for ld in lds]
            ext, err, order = richardson(q)
            rows.append(("unload", dm, r, ext, err, order, "P at delta/delta_max"))
            print("unload", dm, r, q, ext, err, file=sys.stderr)

    # restitution
    vs = [1, 2, 5, 10, 20, 50, 100]
    es = {v: [] for v in vs}
    for m in ms:
        # c_max: loading work must exceed 0.4*100^2
        c_max = 14.0
        curve = load_curve(m, c_max)
        for v in vs:
            if v == 1:
                es[v].append(1.0)
                continue
            target = 0.4 * v * v
            c = brentq(lambda cc: load_work(curve, cc) - target, 1e-6, c_max)
            ld = Loaded(c, m)
            wl = load_work(curve, c)
            es[v].append(np.sqrt(ld.unload_work() / wl))
    for v in vs:
        if v == 1:
            rows.append(("restitution", 1.0, 0.0, 1.0, 0.0, 0.0, "exact"))
            continue
        ext, err, order = richardson(es[v])
        rows.append(("restitution", float(v), 0.0, ext, err, order, "e at v/v_y"))
        print("e", v, es[v], ext, err, file=sys.stderr)

    tmp = args.out + ".tmp"
    with open(tmp, "w") as fh:
        fh.write("# cap_reference.csv: written by tools/reference/cap_reference.py\n")
        fh.write(f"# command: python tools/reference/cap_reference.py --m {args.m}\n")
        fh.write("# units: delta/delta_y, P/P_y, v/v_y (universal cap units, theory.md §12)\n")
        fh.write("# model: load (x = delta/delta_y, value = P/P_y); residual (x = delta_max,"
                 " value = delta_r/delta_max); unload (x = delta_max, y = delta/delta_max,"
                 " value = P/P_y); restitution (x = v/v_y, value = e)\n")
        fh.write("# error: Richardson estimate over m, 2m, 4m ring elements\n")
        fh.write("model,x,y,value,error,order\n")
        for k, x, y, val, err, order, _ in rows:
            fh.write(f"{k},{x:.6g},{y:.6g},{val:.12e},{err:.3e},{order:.3g}\n")
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
