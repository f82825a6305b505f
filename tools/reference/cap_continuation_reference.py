#!/usr/bin/env python3
"""Independent reference for the fully capped continuation of the smooth sphere with the
flow-pressure cap (doc/theory.md section 12, "Beyond a table"): the elastic unloading of a
contact that was fully capped at its turning point, by Sneddon's solution of the
axisymmetric punch (no rings, no egw code), in mpmath.

Units a_y = 1, delta_y = 1, R = E* = 1 (p_y = 2/pi); forces in E* sqrt(R) delta_y^1.5.
Fully capped at Delta_m (contact radius a_m), p = p_y on the disk [0, a_m]: the plastic
displacement fills it, so the unloaded shape inside a_m is Delta_m - w_disk(rho; a_m),
w_disk = (8 a_m/pi^2) E(rho^2/a_m^2) (E the complete elliptic integral, parameter m):
relative to its centre h(rho) = (8 a_m/pi^2)(pi/2 - E(rho^2/a_m^2)), increasing, with
h'(rho) = (8/pi^2)(K - E)/k, k = rho/a_m. Unloading is elastic: a punch of profile h
pressed to a contact radius b = beta a_m has (Sneddon 1965, rho = b sin t)
  Delta - (Delta_m - 4 a_m/pi) = b int_0^{pi/2} h'(b sin t) dt        = a_m D(beta),
  P = 2 b^2 int_0^{pi/2} sin^2 t h'(b sin t) dt                        = a_m^2 G(beta),
  dP/dDelta = 2 b (every axisymmetric elastic contact),
  U = int P dDelta from the residual overlap (beta = 0)                = a_m^3 Uhat(beta),
Uhat(beta) = int_0^beta G D' dbeta' = G D - beta D^2 + int_0^beta D^2 (by parts, dG = 2
beta dD). Checks printed: D(1) = 4/pi (back at Delta_m), G(1) = 2 (P = pi a_m^2 p_y), and
the by-parts Uhat(0.5) against int G D' (mpmath's derivative), each to the quadrature's
accuracy.

Run: python3 tools/reference/cap_continuation_reference.py [--out
test/data/cap_continuation_reference.csv] (mpmath at 20 digits).
Columns: beta, D, G, Uhat (the library's continuation: Delta = Delta_m - 4 a_m/pi + a_m D,
P = a_m^2 G, dP/dDelta = 2 beta a_m, U = a_m^3 Uhat, a_m = alpha(Delta_m) = sqrt(k^2 + 2
Delta_m) - k, k = 8/pi^2, in the units above).
"""
import argparse

import mpmath as mp

mp.mp.dps = 20
C8 = 8 / mp.pi**2


def hp(beta, t):
    """h'(rho) in units where a_m = 1, at k = rho/a_m = beta sin t; K from the
    complementary parameter 1 - k^2 = 1 - beta^2 + beta^2 cos^2 t (exact near the edge,
    where K ~ ln(4/cos t): no rounding of k^2 to 1)."""
    k = beta * mp.sin(t)
    if k == 0:
        return mp.mpf(0)
    m1 = (1 - beta**2) + (beta * mp.cos(t))**2
    kk = mp.pi / (2 * mp.agm(1, mp.sqrt(m1)))
    return C8 * (kk - mp.ellipe(1 - m1)) / k


def D(beta):
    return beta * mp.quad(lambda t: hp(beta, t), [0, mp.pi / 2])


def G(beta):
    return 2 * beta**2 * mp.quad(lambda t: mp.sin(t)**2 * hp(beta, t), [0, mp.pi / 2])


def Uhat_steps(betas):
    """Uhat at increasing betas, by parts: int G dD = G D - int D dG and dG = 2 t dD
    (dP/dDelta = 2b), so Uhat(beta) = G D - beta D^2 + int_0^beta D^2 dt (D alone under
    the integral; its piece up to each beta accumulated)."""
    out, acc, prev = [], mp.mpf(0), mp.mpf(0)
    for beta in betas:
        acc += mp.quad(lambda t: D(t)**2, [prev, beta])
        prev = beta
        d = D(beta)
        out.append(G(beta) * d - beta * d * d + acc)
    return out


BETAS = ["0.05", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9", "0.95",
         "0.98", "0.99", "0.999"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="test/data/cap_continuation_reference.csv")
    args = ap.parse_args()
    print("D(1) - 4/pi =", mp.nstr(D(mp.mpf(1)) - 4 / mp.pi, 5))
    print("G(1) - 2    =", mp.nstr(G(mp.mpf(1)) - 2, 5))
    betas = [mp.mpf(b) for b in BETAS] + [mp.mpf(1)]
    uh = Uhat_steps(betas)
    rows = [(b, D(beta), G(beta), u) for b, beta, u in zip(BETAS, betas, uh)]
    # beta = 1: back at the turning point (the energy the whole unloading returns)
    rows.append(("1", 4 / mp.pi, mp.mpf(2), uh[-1]))
    # check of the by-parts form at one beta: int_0^beta G D' directly
    b = mp.mpf("0.5")
    direct = mp.quad(lambda t: G(t) * mp.diff(D, t), [0, b])
    print("Uhat(0.5) by parts - direct =", mp.nstr(uh[BETAS.index("0.5")] - direct, 5))
    with open(args.out, "w") as f:
        f.write("# fully capped unloading (tools/reference/cap_continuation_reference.py): "
                "Delta = Delta_m - 4 a_m/pi + a_m D, P = a_m^2 G, U = a_m^3 Uhat "
                "(a_y = delta_y = R = E* = 1)\n")
        f.write("# beta,D,G,Uhat\n")
        for b, d, g, u in rows:
            f.write("%s,%s,%s,%s\n" % (b, mp.nstr(d, 17), mp.nstr(g, 17), mp.nstr(u, 17)))
    print("wrote", args.out, len(rows), "rows")


if __name__ == "__main__":
    main()
