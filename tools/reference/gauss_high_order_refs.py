"""F_n(h) of high orders where phi(h) is subnormal but F_n(h) is a normal double.

F_n(h) = Gamma(n+1) phi(h)/h^(n+1) (1 + ...) for large h: at n ~ 100-150 the factor
Gamma(n+1)/h^(n+1) lifts F_n above the doubles' normal range for 37.5 <= h <= 38.7,
where phi(h) itself is subnormal (< 2.2e-308) or nearly so. These values test that
egw's general-order quadrature does not round its result through a subnormal phi
(test_gauss, "high orders where phi(h) is subnormal"; audit25).

Independent of egw: the closed form F_n(h) = Gamma(n+1) exp(-h^2/4) D_{-n-1}(h)/sqrt(2 pi)
(doc/theory.md section 2; mpmath's parabolic cylinder function at 50 digits), checked
against Gauss-Legendre quadrature of the definition to 1e-25.

    python3 tools/reference/gauss_high_order_refs.py
"""
import mpmath as mp

mp.mp.dps = 50
CASES = [(150, 37.5), (150, 37.9), (150, 38.0), (150, 38.3), (150, 38.5), (150, 38.6),
         (120, 37.5), (137.25, 38.1), (100, 37.2)]


def f_pcf(n, h):
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.gamma(n + 1) * mp.exp(-h * h / 4) * mp.pcfd(-n - 1, h) / mp.sqrt(2 * mp.pi)


def f_quad(n, h):
    """The definition by Gauss-Legendre on 256 panels of [0, 20] (the integrand x^n phi(h + x)
    peaks near x = n/h ~ 4 and is below 1e-60 of its peak beyond x = 20)."""
    n, h = mp.mpf(n), mp.mpf(h)
    g = lambda x: mp.exp(n * mp.log(x) - (h + x)**2 / 2) if x > 0 else mp.mpf(0)
    return mp.quad(g, mp.linspace(0, 20, 257), method="gauss-legendre") / mp.sqrt(2 * mp.pi)


for n, h in CASES:
    a, b = f_pcf(n, h), f_quad(n, h)
    assert abs(a - b) <= mp.mpf("1e-25") * abs(a), (n, h, a, b)
    print(f"{n!r:>8} {h!r:>6} {mp.nstr(a, 17, min_fixed=1, max_fixed=0)}")
