#!/usr/bin/env python3
"""Accuracy of egw's C API against independent mpmath values at random points.

Random points (fixed seed) across each documented range of the Gaussian asperity integrals
F_n(h) and dF_n/dh (egw.h: rel <= 1e-14 for n in {0, 1/2, 1, 3/2, 5/2}, <= 1e-12 other n),
the complete elliptic integrals K(k), E(k) (egw.h "a few ulp", README <= 4 ulp), the Hertz
closed forms (README <= 4 ulp), first yield delta_y, v_y (egw.h closed forms) and the
flow-pressure cap's fully plastic limit P -> pi a^2 p_y, a^2/2 + 8 a/pi^2 = delta/delta_y in
units of a_y (doc/theory.md 12). The egw values come from tools/reference/capi_eval.c, a C
program written from egw.h alone, built and run by this script:

    python3 tools/reference/capi_accuracy.py [--cc "cc ... -legw"] [--points N]

Default build: cc against the fpm library in build/ (fpm build --profile release first).
The references are mpmath at 50 digits (F_n by the parabolic cylinder function, checked
against quadrature at 30 digits where both apply); nothing of egw is used for them.
"""
import argparse
import glob
import math
import os
import random
import subprocess
import sys

import mpmath as mp

mp.mp.dps = 50
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DBL_MAX = sys.float_info.max
DBL_MIN = sys.float_info.min


def ulp(x):
    """Spacing of doubles at |x| (subnormal spacing below DBL_MIN)."""
    x = abs(float(x))
    if x < DBL_MIN:
        return 2.0**-1074
    return math.ldexp(1.0, math.frexp(x)[1] - 53)


def gauss_ref(n, h):
    """F_n(h) = Gamma(n+1) exp(-h^2/4) D_{-n-1}(h) / sqrt(2 pi)."""
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.gamma(n + 1) * mp.exp(-h * h / 4) * mp.pcfd(-n - 1, h) / mp.sqrt(2 * mp.pi)


def gauss_ref_deep(n, h):
    """F_n(h) for h < -30 by quadrature over the Gaussian itself, s in [-25, 25] (the
    part below h and beyond 25 is below 1e-130 relatively): the parabolic cylinder
    function cancels catastrophically at |h| ~ 1e99."""
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.quad(lambda s: (s - h)**n * mp.npdf(s), [-25, -5, 0, 5, 25])


def gauss_ref_checked(n, h):
    """gauss_ref at 50 and 70 digits; the two must agree to 1e-30."""
    if h < -30:
        with mp.workdps(50):
            a = gauss_ref_deep(n, h)
        with mp.workdps(70):
            b = gauss_ref_deep(n, h)
        if b != 0 and abs(a / b - 1) > mp.mpf(10)**-30:
            raise RuntimeError(f"reference unstable at n={n} h={h}")
        return b
    with mp.workdps(50):
        a = gauss_ref(n, h)
    with mp.workdps(70):
        b = gauss_ref(n, h)
    if b != 0 and abs(a / b - 1) > mp.mpf(10)**-30:
        raise RuntimeError(f"reference unstable at n={n} h={h}")
    return b


def gauss_deriv_ref(n, h):
    if n == 0:
        return -mp.npdf(mp.mpf(h))
    return -mp.mpf(n) * gauss_ref_checked(n - 1, h)


def flat_ref(psi, k, rho, h):
    """Phi(h) = I_e + (I_ep + 2 I_p)/(K psi) of doc/theory.md 3 (ZMC summits; x = s - h,
    e = 1/psi^2, q = rho_p e, mean pressure p_m/H = 1 - (1 - K) ln(q/x)/ln(q/e), area
    factor 1 + 3 l^2 - 2 l^3, l = (x - e)/(q - e)); psi = 0: F_{3/2}(h). Summit forces in
    units of the Hertz summit's (4/3) E beta^(1/2) sigma^(3/2), from the ZMC law itself."""
    h = mp.mpf(h)
    if psi == 0:
        return gauss_ref_checked(1.5, h)
    psi, k, rho = mp.mpf(psi), mp.mpf(k), mp.mpf(rho)
    e = 1 / psi**2
    q = rho * e
    dens = lambda x: mp.npdf(x + h)
    def cuts(lo, hi):
        pts = [lo] + [c for c in (-h - 8, -h, -h + 8) if lo < c < hi] + [hi]
        return pts
    i_e = mp.quad(lambda x: x**1.5 * dens(x), cuts(0, e))
    def ep(x):
        lam = (x - e) / (q - e)
        pm = 1 - (1 - k) * mp.log(q / x) / mp.log(rho)
        return pm * (1 + 3 * lam**2 - 2 * lam**3) * x * dens(x)
    i_ep = mp.quad(ep, cuts(e, q))
    i_p = (mp.npdf(h + q) - (h + q) * mp.ncdf(-(h + q))) + q * mp.ncdf(-(h + q))
    return i_e + (i_ep + 2 * i_p) / (k * psi)


def build(cc):
    exe = os.path.join(ROOT, "build", "capi_eval")
    src = os.path.join(ROOT, "tools", "reference", "capi_eval.c")
    if cc is None:
        libs = glob.glob(os.path.join(ROOT, "build", "gfortran_*", "egw", "libegw.a"))
        if not libs:
            sys.exit("capi_accuracy: no build/gfortran_*/egw/libegw.a: fpm build --profile release")
        lib = max(libs, key=os.path.getmtime)
        cmd = (f"cc -O2 -I{ROOT}/include {src} {lib} -lfftw3_omp -lfftw3 -llapack -lblas "
               f"-lgfortran -lgomp -lm -o {exe}")
    else:
        cmd = f"{cc.replace('SRC', src)} -o {exe}"
    subprocess.run(cmd, shell=True, check=True)
    return exe


def points(count, rng):
    """(request, kind, reference builder) triples across the documented ranges."""
    hot = [0.0, 0.5, 1.0, 1.5, 2.5]
    out = []
    for _ in range(count):
        n = rng.choice(hot)
        h = rng.uniform(-60.0, 38.6)
        out.append(("gauss", n, h))
    for _ in range(count // 4):   # deep negative h: F_n ~ |h|^n up to the doubles
        n = rng.choice(hot)
        h = -10.0**rng.uniform(1.8, 100.0)
        out.append(("gauss", n, h))
    for _ in range(count // 4):   # the underflow end: subnormal results
        n = rng.choice(hot)
        h = rng.uniform(37.0, 39.5)
        out.append(("gauss", n, h))
    for _ in range(count):
        n = rng.uniform(0.0, 150.0)
        h = rng.uniform(-20.0, 38.0)
        out.append(("gauss", n, h))
    for _ in range(count // 2):
        n = rng.choice(hot + [rng.uniform(0.0, 150.0)])
        h = rng.uniform(-30.0, 38.0)
        out.append(("gaussd", n, h))
    for _ in range(count):
        k = rng.uniform(0.0, 1.0) if rng.random() < 0.5 else 1.0 - 10.0**-rng.uniform(0.0, 16.0)
        if k >= 1.0:
            continue
        out.append((rng.choice(["ellipk", "ellipe"]), k))
    for _ in range(count):
        r = 10.0**rng.uniform(-9.0, 0.0)
        e = 10.0**rng.uniform(6.0, 12.0)
        d = r * 10.0**rng.uniform(-12.0, -1.0)
        out.append(("hertz", r, e, d))
    for _ in range(count // 2):
        r = 10.0**rng.uniform(-9.0, 0.0)
        e = 10.0**rng.uniform(6.0, 12.0)
        py = e * 10.0**rng.uniform(-5.0, -0.3)
        m = 10.0**rng.uniform(-15.0, 0.0)
        out.append(("yield", r, e, py, m))
    for _ in range(count // 4):   # ZMC rough flat over README's ranges, and E-GW's
        psi = 10.0**rng.uniform(-1.0, 2.0) if rng.random() < 0.8 else 0.0
        k = rng.uniform(0.05, 0.95)
        rho = 1.0 + 10.0**rng.uniform(-2.0, math.log10(999.0))
        out.append(("flat", psi, k, rho, rng.uniform(-12.0, 12.0)))
    for _ in range(max(count // 40, 6)):
        r = 10.0**rng.uniform(-6.0, -2.0)
        e = 10.0**rng.uniform(9.0, 11.5)
        py = e * 10.0**rng.uniform(-3.0, -1.5)
        dy = (math.pi * py / (2 * e))**2 * r
        out.append(("cap", r, e, py, dy * 10.0**rng.uniform(1.5, 3.0)))
    return out


def reference(req):
    kind = req[0]
    if kind == "gauss":
        return [gauss_ref_checked(req[1], req[2])]
    if kind == "gaussd":
        return [gauss_deriv_ref(req[1], req[2])]
    if kind == "ellipk":
        return [mp.ellipk(mp.mpf(req[1])**2)]
    if kind == "ellipe":
        return [mp.ellipe(mp.mpf(req[1])**2)]
    if kind == "flat":
        return [flat_ref(*req[1:])]
    r, e = mp.mpf(req[1]), mp.mpf(req[2])
    if kind == "hertz":
        d = mp.mpf(req[3])
        a = mp.sqrt(r * d)
        return [mp.mpf(4) / 3 * e * mp.sqrt(r) * d**1.5, 2 * e * a, a]
    py = mp.mpf(req[3])
    dy = (mp.pi * py / (2 * e))**2 * r
    if kind == "yield":
        m = mp.mpf(req[4])
        w = mp.mpf(8) / 15 * e * mp.sqrt(r) * dy**2.5
        return [dy, mp.sqrt(2 * w / m)]
    # cap: fully plastic disk of radius a, a^2/2 + 8a/pi^2 = Delta in units a_y
    big = mp.mpf(req[4]) / dy
    c = 8 / mp.pi**2
    alpha = -c + mp.sqrt(c * c + 2 * big)
    ay = mp.pi * r * py / (2 * e)
    return [mp.pi * (alpha * ay)**2 * py, None, py]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cc", help="compile command with SRC for the source, e.g. "
                    "\"cc SRC $(pkg-config --cflags --libs egw-static)\"")
    ap.add_argument("--points", type=int, default=400)
    ap.add_argument("--seed", type=int, default=20261130)
    args = ap.parse_args()
    exe = build(args.cc)
    reqs = points(args.points, random.Random(args.seed))
    text = "".join(" ".join([q[0]] + [repr(float(v)) for v in q[1:]]) + "\n" for q in reqs)
    got = subprocess.run([exe], input=text, capture_output=True, text=True, check=True)
    worst = {}
    refused = []
    for q, line in zip(reqs, got.stdout.splitlines()):
        fields = line.split()
        status, vals = int(fields[0]), [float(v) for v in fields[1:]]
        refs = reference(q)
        if status != 0:
            if all(x is None or abs(x) <= DBL_MAX for x in refs):
                refused.append((q, status))
            continue
        for i, ref in enumerate(refs):
            if ref is None:
                continue
            v = vals[i]
            if abs(ref) < DBL_MIN:   # subnormal or zero result: error in subnormal ulps
                err_ulp = float(abs(mp.mpf(v) - ref) / mp.mpf(2)**-1074)
                rel = 0.0
                key = (q[0] + "[subnormal]", i)
            else:
                err_ulp = float(abs(mp.mpf(v) - ref) / mp.mpf(ulp(ref)))
                rel = float(abs(mp.mpf(v) / ref - 1))
                hot = q[0].startswith("gauss") and q[1] in (0.0, 0.5, 1.0, 1.5, 2.5)
                key = (q[0] + ("[hot n]" if hot else "[other n]" if q[0].startswith("gauss")
                               else ""), i)
            old = worst.get(key)
            if old is None or rel > old[0] or (rel == old[0] and err_ulp > old[1]):
                worst[key] = (rel, err_ulp, q)
    names = {"hertz": ["force", "stiffness", "contact_radius"],
             "yield": ["delta_y", "velocity_y"], "cap": ["force", "", "max_pressure"],
             "flat": ["pressure"]}
    print(f"{len(reqs)} points, seed {args.seed}")
    for (kind, i), (rel, err_ulp, q) in sorted(worst.items()):
        label = kind + (":" + names[kind.split("[")[0]][i] if kind.split("[")[0] in names else "")
        print(f"{label:28s} max rel {rel:9.2e}  max {err_ulp:8.2f} ulp  at {q[1:]}")
    for q, status in refused:
        print(f"refused (status {status}) although the reference is a double: {q}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
