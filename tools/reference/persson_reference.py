"""Independent reference values of Persson's mean separation u(p) (egw_flat_persson,
doc/theory.md section 11) for test/test_flat_law.f90.

Evaluates the theory's formula as published, without egw's substitutions:
  u(p) = sqrt(pi) int_{q0}^{q1} dq q^2 C(q) w(q) int_p^inf (dp'/p')
         [gamma + 3(1 - gamma) P(q, p')^2] exp(-(w(q) p'/E*)^2),
  w(q) = (pi int_{q0}^q q^3 C)^(-1/2),  P = erf(1/(2 sqrt G)),
  G = (pi/4)(E*/p')^2 int_{q0}^q q^3 C,
by nested adaptive quadrature (scipy.integrate.quad, inner integral in ln p', outer in
ln q split at the roll-off), for the self-affine spectrum below (Hurst 0.8, rms height
1e-6 m, plateau from 2 pi/1 mm to the roll-off 2 pi/0.1 mm, power law to 2 pi/1 um;
E* = 1 GPa, gamma = 0.42). Each value is computed at two tolerances (1e-8 and 1e-10
relative); their difference is written as the estimated error.

    python3 tools/reference/persson_reference.py > test/data/persson_reference.csv
"""
import numpy as np
from scipy import integrate, special

H, HRMS, E, GAMMA = 0.8, 1e-6, 1e9, 0.42
QL, QR, QS = 2 * np.pi / 1e-3, 2 * np.pi / 1e-4, 2 * np.pi / 1e-6
TAIL = QR ** 2 * (1 - (QS / QR) ** (-2 * H)) / (2 * H)
C0 = HRMS ** 2 / (2 * np.pi * (0.5 * (QR ** 2 - QL ** 2) + TAIL))


def psd(q):
    return C0 if q < QR else C0 * (q / QR) ** (-2 * (1 + H))


def m3(q):
    """int_{q0}^q q'^3 C dq' (closed form for the two power laws)."""
    if q <= QR:
        return C0 * (q ** 4 - QL ** 4) / 4
    return C0 * (QR ** 4 - QL ** 4) / 4 + C0 * QR ** 4 * ((q / QR) ** (2 - 2 * H) - 1) / (2 - 2 * H)


def inner(q, p, tol):
    w = (np.pi * m3(q)) ** -0.5

    def f(lp):          # integrand in ln p'
        pp = np.exp(lp)
        g = np.pi / 4 * (E / pp) ** 2 * m3(q)
        big_p = special.erf(1 / (2 * np.sqrt(g)))
        return (GAMMA + 3 * (1 - GAMMA) * big_p ** 2) * np.exp(-(w * pp / E) ** 2)
    # exp(-(w p'/E*)^2) < 1e-27 beyond p' = 8 E*/w
    top = max(np.log(p), np.log(8 * E / w)) + 1.0
    return integrate.quad(f, np.log(p), top, limit=500, epsabs=0, epsrel=tol)[0]


def u_of_p(p, tol):
    def f(lq):
        q = np.exp(lq)
        return q ** 3 * psd(q) * (np.pi * m3(q)) ** -0.5 * inner(q, p, tol)
    parts = [integrate.quad(f, a, b, limit=500, epsabs=0, epsrel=tol)[0]
             for a, b in ((np.log(QL), np.log(QR)), (np.log(QR), np.log(QS)))]
    return np.sqrt(np.pi) * sum(parts)


def u0():
    """The large-separation scale u0 = sqrt(pi) gamma int q^2 C w dq (p ~ exp(-u/u0))."""
    f = lambda lq: np.exp(lq) ** 3 * psd(np.exp(lq)) * (np.pi * m3(np.exp(lq))) ** -0.5
    parts = [integrate.quad(f, a, b, limit=500, epsabs=0, epsrel=1e-12)[0]
             for a, b in ((np.log(QL), np.log(QR)), (np.log(QR), np.log(QS)))]
    return np.sqrt(np.pi) * GAMMA * sum(parts)


def main():
    print("# Persson u(p): self-affine PSD, Hurst 0.8, rms height 1e-6 m, q from 2 pi/1e-3 "
          "(plateau to 2 pi/1e-4) to 2 pi/1e-6 rad/m; E* = 1e9 Pa; gamma = 0.42")
    print("# made by tools/reference/persson_reference.py (scipy quad, nested); err = "
          "|u(1e-8) - u(1e-10)| / u")
    print("p_over_E,u_m,err")
    for pr in (1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 5e-2):
        a, b = u_of_p(pr * E, 1e-8), u_of_p(pr * E, 1e-10)
        print(f"{pr:.17g},{b:.17g},{abs(a - b) / b:.3g}")
    print(f"# u0 = {u0():.17g} m (sqrt(pi) gamma int q^2 C w dq: p ~ exp(-u/u0) as p -> 0)")


if __name__ == "__main__":
    main()

