#!/usr/bin/env python3
"""Reference values for the egw_gauss and egw_asperity tests -> test/ref_gauss.f90.

Everything is computed at 50 significant digits by mpmath quadrature of the DEFINITIONS
(doc/theory.md section 2): F_n(h) = int_h^inf (s-h)^n phi(s) ds, the truncated ZMC integrals
I_e, I_ep, I_p with x = s - h, and their h-derivatives as d/dh under the integral sign,
dI/dh = -int g(x) (h+x) phi(h+x) dx, which needs no boundary terms.  F_n is cross-checked
against the parabolic-cylinder form Gamma(n+1) e^{-h^2/4} D_{-n-1}(h)/sqrt(2 pi) and the
script stops if the two disagree beyond 1e-25 relative (two quadratures of one integral
must agree to 1e-18).  Run:
    python3 tools/reference/gauss_refs.py
(takes about 20 minutes on two cores).  The rough-flat law of egw_asperity,
p = I_e + (I_ep + 2 I_p)/(K psi) (doc/theory.md section 3, misprint 4), and dp/dh are formed
here from the 50-digit integrals; its psi = 0 case is F_{3/2}, dp/dh = -(3/2) F_{1/2}.
"""
import multiprocessing
import os
import random
import sys

try:
    import mpmath as mp
except ImportError:  # the script installs what it needs
    import subprocess
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mpmath"])
    import mpmath as mp

mp.mp.dps = 50
PHI0 = 1 / mp.sqrt(2 * mp.pi)


def phi(z):
    return PHI0 * mp.exp(-z * z / 2)


def breakpoints(a, b, h):
    """Points that resolve the Gaussian factor phi(h + x) of an integrand on [a, b]."""
    c = -h
    pts = {a}
    if b != mp.inf:
        pts.add(b)
    for k in range(-14, 15):
        pts.add(c + k)
    for end in (a, b):
        if end == mp.inf:
            continue
        scale = 1 / (abs(h + end) + 1)
        for t in (0.25, 0.5, 1, 2, 4, 8, 16, 32, 64, 128):
            pts.add(end + t * scale)
            pts.add(end - t * scale)
    inside = sorted(p for p in pts if a <= p and (b == mp.inf or p <= b))
    # geometric points towards the left end, where x^n and log x have branch points
    if len(inside) > 1:
        first = inside[1]
        for k in range(1, 12):
            pts.add(a + (first - a) * mp.mpf(4)**(-k))
        inside = sorted(p for p in pts if a <= p and (b == mp.inf or p <= b))
    if b == mp.inf:
        inside.append(mp.inf)
    return inside


def quad(f, a, b, h):
    """Integral of f over [a, b], scaled to O(1) first (mpmath's error control is absolute)
    and done twice by tanh-sinh on two different sets of breakpoints; the script stops if
    the two disagree."""
    pts = breakpoints(mp.mpf(a), b if b == mp.inf else mp.mpf(b), mp.mpf(h))
    return quad_on(f, pts, a, b, h)


def quad_on(f, pts, a, b, h):
    probe = [p for p in pts if p != mp.inf] + [(u + v) / 2 for u, v in zip(pts[:-1], pts[1:])
                                              if v != mp.inf]
    scale = max(abs(f(p)) for p in probe if p > 0) or mp.mpf(1)
    g = lambda x: f(x) / scale
    v1 = mp.quad(g, pts)
    coarse = pts[::2] if pts[-1] == pts[::2][-1] else pts[::2] + [pts[-1]]
    v2 = mp.quad(g, coarse, maxdegree=8)
    if abs(v1 - v2) > mp.mpf("1e-18") * max(abs(v1), mp.mpf("1e-300")):
        raise SystemExit(f"quadratures disagree on [{a}, {b}] at h = {h}: {v1} {v2}")
    return v1 * scale


def f_n(n, h):
    n, h = mp.mpf(n), mp.mpf(h)
    if n >= 0:
        return quad(lambda x: x**n * phi(h + x), 0, mp.inf, h)
    # x = u^m, m = 1/(n+1), removes the x^n singularity: x^n dx = m du
    m = 1 / (n + 1)
    pts = [p**(n + 1) if p != mp.inf else p for p in breakpoints(mp.mpf(0), mp.inf, h)]
    return m * quad_on(lambda u: phi(h + u**m), pts, 0, mp.inf, h)


def f_n_pcf(n, h):
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.gamma(n + 1) * mp.exp(-h * h / 4) * mp.pcfd(-n - 1, h) / mp.sqrt(2 * mp.pi)


def zmc(h, e, q, k):
    h, e, q, k = map(mp.mpf, (h, e, q, k))
    lnqe = mp.log(q / e)

    def g_ep(x):
        lam = (x - e) / (q - e)
        return (1 - (1 - k) * mp.log(q / x) / lnqe) * (1 + 3 * lam**2 - 2 * lam**3) * x

    i_e = quad(lambda x: x**1.5 * phi(h + x), 0, e, h)
    i_ep = quad(lambda x: g_ep(x) * phi(h + x), e, q, h)
    i_p = quad(lambda x: x * phi(h + x), q, mp.inf, h)
    di_e = -quad(lambda x: x**1.5 * (h + x) * phi(h + x), 0, e, h)
    di_ep = -quad(lambda x: g_ep(x) * (h + x) * phi(h + x), e, q, h)
    di_p = -quad(lambda x: x * (h + x) * phi(h + x), q, mp.inf, h)
    return [i_e, i_ep, i_p, di_e, di_ep, di_p]


def dbl(v):
    """Fortran literal of the double nearest v (Python's shortest round-trip repr)."""
    x = float(v)
    if x == 0:
        return "0.0_dp"
    r = repr(x)
    if "e" not in r and "." not in r:
        r += ".0"
    return r + "_dp"


def table(name, rows, doc):
    """rows: list of equal-length lists -> real(dp) parameter name(ncol, nrow) in chunks."""
    ncol = len(rows[0])
    out = [f"   !> {doc}"]
    chunk = 40
    parts = []
    for ic in range(0, len(rows), chunk):
        part = rows[ic:ic + chunk]
        pname = f"{name}_{ic // chunk + 1}"
        parts.append(pname)
        lines = [f"   real(dp), parameter :: {pname}({ncol}, {len(part)}) = reshape([ &"]
        for ir, r in enumerate(part):  # one record per line, or per group of lines
            vals = [dbl(v) for v in r]
            per = ncol if ncol <= 4 else 3
            for i in range(0, len(vals), per):
                last = ir == len(part) - 1 and i + per >= len(vals)
                lines.append("      & " + ", ".join(vals[i:i + per]) + ("], &" if last else ", &"))
        lines.append(f"      & [{ncol}, {len(part)}])")
        out.append("\n".join(lines))
    out.append(f"   real(dp), parameter, public :: {name}({ncol}, {len(rows)}) = reshape([ &")
    for i in range(0, len(parts), 6):
        end = ", &" if i + 6 < len(parts) else f"], [{ncol}, {len(rows)}])"
        out.append("      & " + ", ".join(parts[i:i + 6]) + end)
    return "\n".join(out)


def main():
    random.seed(20260517)
    # ---- F_n and dF_n/dh on a grid that avoids the fit nodes --------------------------
    hs = [-1000.0, -300.0, -45.5, -20.25, -12.5, -12.0, -11.9375, -6.03125, -1.0, -0.0625,
          0.0, 0.0625, 1.0, 2.0, 6.0, -5.0, 7.9375, 8.0, 11.75, 15.9, 23.8, 30.1, 35.5, 37.0,
          37.6, 38.2, 38.6, 39.0, 40.0, 45.0]
    hs += [round(random.uniform(-12, 39), 6) for _ in range(34)]
    fitted = ["-0.5", "0", "0.5", "1", "1.5", "2.5"]
    general = ["0.3", "2", "3.7", "7", "-0.7"]
    frows = []
    for ns in fitted + general:
        n = mp.mpf(ns)
        hset = hs if ns in fitted else hs[::2]
        for h in hset:
            f = f_n(n, h)
            fp = f_n_pcf(n, h)
            if abs(f - fp) > mp.mpf("1e-25") * abs(fp):
                raise SystemExit(f"quad and pcfd disagree: n={ns} h={h} {f} {fp}")
            if n == 0:
                df = -phi(mp.mpf(h))
            elif n > 0:  # dF_n/dh = -n F_{n-1}, here from the parabolic-cylinder form
                df = -n * f_n_pcf(n - 1, h)
            else:
                df = mp.mpf(0)  # the API defines dF_n/dh for n >= 0 only; unused
            frows.append([n, mp.mpf(h), f, df])
        print("F_n done", ns, file=sys.stderr)
    # ---- ZMC integrals ---------------------------------------------------------------
    zrows = []
    for psi in (0.1, 0.5, 1.0, 3.0, 10.0, 100.0):
        e = 1.0 / (psi * psi)  # IEEE double arithmetic, as egw_asperity forms e and q
        for rho, k in ((1.01, 0.6), (54.0, 0.1), (1000.0, 0.95)):
            q = rho * e
            cands = [-2 * q - 3, -q - 4, -q, -(q + e) / 2, -e - 1.5, -e, -e / 2, -1.0, 0.0,
                     0.7, 2.5, 6.0, 15.0, 38.0]
            if psi in (0.5, 3.0):
                cands = cands[::2]
            for h in cands:
                h = mp.mpf(float(mp.nstr(h, 12)))  # a short decimal, exactly a double
                zrows.append([h, mp.mpf(e), mp.mpf(q), mp.mpf(k), mp.mpf(psi), mp.mpf(rho)]
                             + [None] * 8)
    with multiprocessing.Pool(2) as pool:
        values = pool.starmap(zmc, [(r[0], r[1], r[2], r[3]) for r in zrows])
    for r, (i_e, i_ep, i_p, di_e, di_ep, di_p) in zip(zrows, values):
        c = 1 / (r[3] * r[4])  # 1/(K psi), doc/theory.md section 3
        r[6:] = [i_e, i_ep, i_p, di_e, di_ep, di_p, i_e + c * (i_ep + 2 * i_p),
                 di_e + c * (di_ep + 2 * di_p)]
    print("ZMC done", len(zrows), file=sys.stderr)

    write_module(frows, zrows)


def write_module(frows, zrows):
    out = os.path.join(os.path.dirname(__file__), "..", "..", "test", "ref_gauss.f90")
    zmc_doc = ("columns: h, e, q, K, psi, rho_p, I_e, I_ep, I_p, dI_e/dh, dI_ep/dh, dI_p/dh,"
               "\n   !> p, dp/dh (p = I_e + (I_ep + 2 I_p)/(K psi))")
    text = f"""!> GENERATED by tools/reference/gauss_refs.py -- do not edit by hand.
!> mpmath (50 digits) quadrature of the definitions of F_n(h) and of the ZMC integrals.
module ref_gauss
   use egw_kinds, only: dp
   implicit none
   private

{table("ref_fn", frows, "columns: n, h, F_n(h), dF_n/dh (0 where n < 0)")}

{table("ref_zmc", zrows, zmc_doc)}

end module ref_gauss
"""
    with open(out, "w") as f:
        f.write(text)
    print("wrote", os.path.normpath(out), len(frows), len(zrows), file=sys.stderr)


if __name__ == "__main__":
    main()
