#!/usr/bin/env python3
"""Independent reference for the rough sphere on unloading (egw issue 10, item 3).

Extends sphere_reference.py (imported: its panels, half-space operator, Newton and adaptive
refinement; nothing from the Fortran code) with the doc/theory.md section 8 unloading law:

  Z_u(h, h_min) = int_{t*}^inf fhat(t) ((D(t) - Delta)/D(t))^{3/2} phi(t + h_min) dt,
  Delta = h - h_min >= 0,  D(t) = min(t, fhat(t)/sqrt(Ahat(t))),  D(t*) = Delta,

and Z(h) (the loading law) for h < h_min.  fhat is the ZMC asperity force in units of
(4/3) E beta^{1/2} sigma^{3/2}, Ahat its contact area / (pi beta sigma).  The integral is
computed here in double precision by Gauss-Legendre on pieces split at the kinks of fhat
(e, q) and at the points where D changes branch (found numerically), with t = t* + x^2 on
the first piece (removes the (D - Delta)^{3/2} edge); dZ_u/dh by differentiating under the
integral.  The sphere: load to delta_max with the loading law (sphere_reference.solve),
keep d_max(r) (panel interpolation of the converged w_G plus the base gap; beyond the last
panel w_G falls like 1/r), solve the same problem at delta <= delta_max with
p_G = C Z_u(d(r), d_max(r)).

  python tools/reference/sphere_unload_reference.py generate  # test/data/sphere_unload_reference.csv
  python tools/reference/sphere_unload_reference.py generate --set kinks
                                                  # test/data/sphere_unload_reference_kinks.csv
  python tools/reference/sphere_unload_reference.py generate --set tail
                                                  # test/data/sphere_unload_reference_tail.csv
  python tools/reference/sphere_unload_reference.py verify    # Z_u checks against mpmath
"""
import argparse
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sphere_reference as sr  # noqa: E402  (first: it installs numpy, scipy, mpmath if missing)
import numpy as np  # noqa: E402

SQRT2PI = math.sqrt(2.0 * math.pi)


class UnloadLaw:
    """fhat, Ahat, D and Z_u for one (psi, K, rho_p); psi = 0: elastic summits."""

    def __init__(self, psi, K, rho, n_sub=12, n_gl=12):
        self.psi, self.K, self.rho = float(psi), float(K), float(rho)
        self.elastic = psi <= 0.0
        self.e = 1.0 / psi ** 2 if psi > 0 else math.inf
        self.q = rho * self.e
        self.xg, self.wg = np.polynomial.legendre.leggauss(n_gl)
        self.n_sub = n_sub
        self.kinks = [] if self.elastic else [self.e, self.q] + self._branch_points()

    def fhat(self, t):
        t = np.asarray(t, dtype=float)
        if self.elastic:
            return np.maximum(t, 0.0) ** 1.5
        e, q, K = self.e, self.q, self.K
        tt = np.maximum(t, 1e-300)
        lam = np.clip((tt - e) / (q - e), 0.0, 1.0)
        c = 1.0 + 3.0 * lam ** 2 - 2.0 * lam ** 3
        m = 1.0 - (1.0 - K) * np.log(q / tt) / math.log(q / e)
        f = np.where(tt <= e, tt ** 1.5,
                     np.where(tt <= q, math.sqrt(e) * tt * m * c / K,
                              2.0 * math.sqrt(e) * tt / K))
        return np.where(t > 0.0, f, 0.0)

    def ahat(self, t):
        t = np.asarray(t, dtype=float)
        if self.elastic:
            return np.maximum(t, 0.0)
        e, q = self.e, self.q
        lam = np.clip((t - e) / (q - e), 0.0, 1.0)
        c = 1.0 + 3.0 * lam ** 2 - 2.0 * lam ** 3
        return np.where(t <= e, t, np.where(t <= q, t * c, 2.0 * t))

    def D(self, t):
        """u_m - u_r at u_m = t (increasing in t)."""
        t = np.asarray(t, dtype=float)
        if self.elastic:
            return t
        tt = np.maximum(t, 1e-300)
        return np.where(t > 0.0, np.minimum(tt, self.fhat(tt) / np.sqrt(self.ahat(tt))), 0.0)

    def _branch_points(self):
        """Where t - fhat/sqrt(Ahat) changes sign (D switches branch), t > e."""
        g = lambda t: t - float(self.fhat(t)) / math.sqrt(float(self.ahat(t)))  # noqa: E731
        grid = np.concatenate([np.geomspace(self.e * (1 + 1e-9), self.q * 0.999999, 400),
                               np.geomspace(self.q * 1.000001, self.q * 1e4, 200)])
        vals = np.array([g(t) for t in grid])
        out = []
        for i in range(len(grid) - 1):
            if vals[i] == 0.0 or vals[i] * vals[i + 1] < 0.0:
                a, b = grid[i], grid[i + 1]
                for _ in range(200):
                    mid = 0.5 * (a + b)
                    if g(a) * g(mid) <= 0.0:
                        b = mid
                    else:
                        a = mid
                out.append(0.5 * (a + b))
        return out

    def t_star(self, delta):
        """D^{-1}(Delta) by bisection (vectorised)."""
        delta = np.asarray(delta, dtype=float)
        lo = np.zeros_like(delta)
        hi = np.maximum(2.0 * delta, 1.0)
        while True:
            bad = self.D(hi) < delta
            if not bad.any():
                break
            hi = np.where(bad, 2.0 * hi, hi)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            up = self.D(mid) >= delta
            hi = np.where(up, mid, hi)
            lo = np.where(up, lo, mid)
        return hi

    def zu(self, h, hmin):
        """Z_u(h, hmin) and dZ_u/dh at fixed hmin, for h >= hmin (arrays)."""
        h = np.asarray(h, dtype=float)
        hmin = np.asarray(hmin, dtype=float)
        delta = h - hmin
        ts = self.t_star(delta)
        lo = np.maximum(ts, -hmin - 10.0)
        hi = np.maximum(lo, -hmin) + 12.0
        # piece boundaries: lo, kinks inside (lo, hi), hi; padded to a fixed count
        nk = len(self.kinks)
        b = np.empty((len(h), nk + 2))
        b[:, 0] = lo
        for j, k in enumerate(self.kinks):
            b[:, j + 1] = np.clip(k, lo, hi)
        b[:, -1] = hi
        b = np.sort(b, axis=1)
        val = np.zeros_like(h)
        der = np.zeros_like(h)
        for j in range(nk + 1):
            a0, a1 = b[:, j], b[:, j + 1]
            # substitution t = t* + x^2 on the piece that starts at the edge t*
            sub = (a0 <= lo) & (ts >= lo)
            L = a1 - a0
            xs_hi = np.where(sub, np.sqrt(np.maximum(L, 0.0)), L)
            for s in range(self.n_sub):
                x0 = xs_hi * s / self.n_sub
                x1 = xs_hi * (s + 1) / self.n_sub
                x = 0.5 * (x0 + x1)[:, None] + 0.5 * (x1 - x0)[:, None] * self.xg[None, :]
                w = 0.5 * (x1 - x0)[:, None] * self.wg[None, :]
                t = np.where(sub[:, None], a0[:, None] + x * x, a0[:, None] + x)
                jac = np.where(sub[:, None], 2.0 * x, 1.0)
                Dt = self.D(t)
                gap = np.maximum(Dt - delta[:, None], 0.0)
                f = self.fhat(t)
                ph = np.exp(-0.5 * (t + hmin[:, None]) ** 2) / SQRT2PI
                Dsafe = np.where(Dt > 0.0, Dt, 1.0)
                ratio = np.where(Dt > 0.0, gap / Dsafe, 0.0)
                val += np.sum(w * jac * f * ratio ** 1.5 * ph, axis=1)
                der += np.sum(w * jac * f * (-1.5) * np.sqrt(ratio) / Dsafe * ph, axis=1)
        return val, der


class UnloadProblem(sr.Problem):
    """Sphere_reference Problem with the unloading law at a fixed closest-approach field."""

    def __init__(self, model, delta, mu, psi, K, rho, loaded, loaded_prob, zu_rule=(12, 12)):
        super().__init__(model, delta, mu, psi, K, rho)
        self.law = UnloadLaw(psi if model == "EPGW" else 0.0, K, rho, n_sub=zu_rule[0],
                             n_gl=zu_rule[1])
        self.loaded_pan = loaded["pan"]
        self.loaded_u = loaded["u"]
        self.loaded_prob = loaded_prob
        self._hmin = None

    def dmax(self, r):
        r = np.asarray(r, dtype=float)
        pan, u = self.loaded_pan, self.loaded_u
        rb = pan.breaks[-1]
        w = np.empty_like(r)
        inside = r <= rb
        w[inside] = pan.interp(u, r[inside])
        # beyond the last panel: the value at the outer radius continued like 1/r
        w_end = pan.interp(u, np.array([rb]))[0]
        w[~inside] = w_end * rb / r[~inside]
        return w + self.loaded_prob.z(r)

    def z(self, r):
        # the solver evaluates pg at the nodes whose base gap it asked for last
        self._hmin = self.dmax(r)
        return super().z(r)

    def pg(self, d):
        d = np.asarray(d, dtype=float)
        hmin = self._hmin
        v, dv = self.phi(d)
        up = d >= hmin
        if up.any():
            vu, dvu = self.law.zu(d[up], hmin[up])
            v = v.copy()
            dv = dv.copy()
            v[up] = vu
            dv[up] = dvu
        return self.C * v, self.C * dv


_LOADED = {}


def unload_point(model, ds, ds_max, mu, psi, K, rho, zu_rule=(12, 12)):
    """The loading study at ds_max and the unloading study at ds; zu_rule: (sub-intervals,
    Gauss points) of each piece of the Z_u quadrature."""
    lp = sr.Problem(model, ds_max, mu, psi, K, rho)
    key = (model, ds_max, mu, psi, K, rho)
    if key not in _LOADED:
        _LOADED[key] = sr.study(lp)
    loaded = _LOADED[key]
    up = UnloadProblem(model, ds, mu, psi, K, rho, loaded, lp, zu_rule)
    r = sr.study(up)
    return loaded, r


POINTS = (
    # model, delta/sigma, delta_max/sigma, mu, psi, K
    ("EPGW", 8.0, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", 5.0, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", 2.0, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", 0.0, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", -1.0, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", 9.9, 10.0, 4.0, 2.0, 0.6),
    ("EPGW", 1.0, 3.0, 1.0, 4.0, 0.4),
    ("EPGW", -0.5, 3.0, 1.0, 4.0, 0.4),
    ("EPGW", 20.0, 50.0, 10.0, 1.0, 0.8),
    ("EPGW", 45.0, 50.0, 10.0, 1.0, 0.8),
    ("EPGW", -1.0, 1.0, 4.0, 10.0, 0.6),
    ("EPGW", 0.5, 1.0, 4.0, 10.0, 0.6),
)

# psi = 10 after delta_max = 2 sigma (mu 4, K 0.6): d - d_max crosses several kinks of Z_u
# in Delta close together; the solver's rel_tol 1e-6/1e-7/1e-8 answers there disagreed by
# more than its error estimate (doc/benchmarks.md).  Kept apart from POINTS (the bench's
# 12 cases) in test/data/sphere_unload_reference_kinks.csv.
KINK_POINTS = (
    ("EPGW", -0.5, 2.0, 4.0, 10.0, 0.6),
    ("EPGW", 0.0, 2.0, 4.0, 10.0, 0.6),
    ("EPGW", 0.5, 2.0, 4.0, 10.0, 0.6),
    ("EPGW", 1.0, 2.0, 4.0, 10.0, 0.6),
)

# Separated contacts far below their turning point (the force 3e-5..1e-12 of the loading
# force at delta_max): the field d_max(r) of a history loaded at the unloading solve's
# rel_tol left errors of 1e-7..6e-7 at every unloading rel_tol (doc/benchmarks.md);
# delta -1 after 10 (5e-9 of it): 5.8e-7 with a history at 1e-9, 1.3e-8 at 1e-10.
# test/data/sphere_unload_reference_tail.csv.
TAIL_POINTS = (
    ("EPGW", -0.8, 10.0, 4.0, 10.0, 0.6),
    ("EPGW", -0.8, 2.0, 4.0, 10.0, 0.6),
    ("EPGW", -1.6, 2.0, 4.0, 5.0, 0.6),
    ("EPGW", -1.0, 10.0, 4.0, 10.0, 0.6),
)

HEADER = """\
# egw reference data: rough sphere unloaded from delta_max to delta (doc/theory.md section 8)
# generated by tools/reference/sphere_unload_reference.py generate (independent Python solver)
# scaled variables R = E* = sigma = 1; rho_p = 54
# columns: model, delta/sigma, delta_max/sigma, mu, psi, K, P_unload, its est. rel. error,
#   dP_unload/d delta, its est. rel. error, P_load(delta_max)
"""


# Z_u quadrature rules of the kinks set: the value from FINE_RULE, its error estimate the
# larger of the study's and the difference to CHECK_RULE.  The default (12, 12) rule is
# 4.4e-9 off at delta -0.5 after delta_max 2, psi 10 (seen against (24, 20) and (48, 24),
# which agree to 1e-12), far more than the study's own estimate (which cannot see it: every
# level uses the same Z_u).
FINE_RULE = (48, 24)
CHECK_RULE = (24, 20)


def generate(path, points=POINTS, rules=None, name=None):
    lines = []
    t0 = time.time()
    for model, ds, dsm, mu, psi, K in points:
        if rules is None:
            loaded, r = unload_point(model, ds, dsm, mu, psi, K, 54.0)
        else:
            loaded, r = unload_point(model, ds, dsm, mu, psi, K, 54.0, rules[0])
            _, rc = unload_point(model, ds, dsm, mu, psi, K, 54.0, rules[1])
            r = dict(r)
            r["P_err"] = max(r["P_err"], abs(rc["P"] / r["P"] - 1.0))
            r["dP_err"] = max(r["dP_err"], abs(rc["dP"] / r["dP"] - 1.0))
        lines.append("%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.16e,%.2e,%.16e,%.2e,%.16e\n"
                     % (model, ds, dsm, mu, psi, K, r["P"], r["P_err"], r["dP"], r["dP_err"],
                        loaded["P"]))
        print(lines[-1].strip(), "%.0f s" % (time.time() - t0), flush=True)
    with open(path + ".tmp", "w") as f:
        if rules is None:
            f.write(HEADER)
        else:
            f.write(HEADER.replace("generate (", "generate --set %s (" % name)
                    .replace("rho_p = 54\n", "rho_p = 54; Z_u by the (sub-intervals, Gauss points) "
                             "rule %s, error estimates\n#   include the difference to %s\n"
                             % (str(rules[0]), str(rules[1]))))
        f.write("model,delta_over_sigma,delta_max_over_sigma,mu,psi,K,P_scaled,P_rel_err,"
                "dP_scaled,dP_rel_err,P_load_max_scaled\n")
        f.writelines(lines)
    os.replace(path + ".tmp", path)


def quad_zu(law, h, hmin):
    """Z_u by scipy's adaptive quadrature in the untransformed variable t (an independent
    check of the piecewise Gauss rule with the t* + x^2 substitution)."""
    from scipy.integrate import quad
    delta = h - hmin
    ts = float(law.t_star(np.array([delta]))[0])

    def f(t):
        Dt = float(law.D(np.array([t]))[0])
        if Dt <= delta:
            return 0.0
        return float(law.fhat(np.array([t]))[0]) * ((Dt - delta) / Dt) ** 1.5 \
            * math.exp(-0.5 * (t + hmin) ** 2) / SQRT2PI
    pts = [k for k in law.kinks if ts < k < ts + 40.0]
    return quad(f, ts, ts + 40.0, points=pts or None, limit=500, epsabs=0.0, epsrel=1e-13)[0]


def verify():
    ok = True
    for psi, K in ((2.0, 0.6), (4.0, 0.4), (1.0, 0.8), (10.0, 0.6), (0.0, 0.6)):
        law = UnloadLaw(psi, K, 54.0)
        phi = sr.get_phi(psi, K, 54.0)
        hs = np.array([-3.0, -1.0, 0.0, 0.5, 2.0])
        # Z_u(h, h) = Z(h)
        v, _ = law.zu(hs, hs)
        z, _ = phi(hs)
        e1 = np.max(np.abs(v / z - 1.0))
        # against mpmath in the untransformed variable
        e2 = 0.0
        for h, hm in ((-0.5, -0.6), (-0.9, -1.2), (0.1, -0.1), (-1.8, -2.0), (1.0, 0.9)):
            a = law.zu(np.array([h]), np.array([hm]))[0][0]
            b = quad_zu(law, h, hm)
            e2 = max(e2, abs(a / b - 1.0))
        # derivative by central differences
        h0, hm = np.array([-0.9]), np.array([-1.2])
        eps = 1e-5
        d_num = (law.zu(h0 + eps, hm)[0] - law.zu(h0 - eps, hm)[0]) / (2 * eps)
        e3 = abs(law.zu(h0, hm)[1][0] / d_num[0] - 1.0)
        flag = e1 < 1e-10 and e2 < 1e-8 and e3 < 1e-6
        ok = ok and flag
        print("psi=%g K=%g: Z_u(h,h)/Z-1 %.1e, vs scipy quad %.1e, dZ_u/dh vs diff %.1e %s"
              % (psi, K, e1, e2, e3, "ok" if flag else "FAIL"))
    return 0 if ok else 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("generate")
    g.add_argument("--out", default=None)
    g.add_argument("--set", choices=("main", "kinks", "tail"), default="main",
                   help="main: POINTS -> test/data/sphere_unload_reference.csv; kinks: "
                   "KINK_POINTS -> test/data/sphere_unload_reference_kinks.csv; tail: "
                   "TAIL_POINTS -> test/data/sphere_unload_reference_tail.csv")
    sub.add_parser("verify")
    args = ap.parse_args(argv)
    if args.cmd == "verify":
        return verify()
    if args.set == "kinks":
        generate(args.out or "test/data/sphere_unload_reference_kinks.csv", KINK_POINTS,
                 (FINE_RULE, CHECK_RULE), "kinks")
    elif args.set == "tail":
        generate(args.out or "test/data/sphere_unload_reference_tail.csv", TAIL_POINTS,
                 (FINE_RULE, CHECK_RULE), "tail")
    else:
        generate(args.out or "test/data/sphere_unload_reference.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
