"""Reference values for test/test_rough_sphere.f90 (far-apart rigid limit).

F_n(h) = int_h^inf (s - h)^n phi(s) ds = Gamma(n+1) exp(-h^2/4) D_{-n-1}(h)/sqrt(2 pi)
(parabolic cylinder function, doc/theory.md §2), cross-checked by quadrature on a fine split
of the integration range (phi(x + h) decays on a scale 1/h). 30 digits; the output is
pasted into test/ref_rough_sphere.f90. Run: python3 tools/reference/rough_sphere_refs.py
"""
try:
    import mpmath as mp
except ImportError:  # pragma: no cover
    import subprocess, sys
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mpmath"])
    import mpmath as mp

mp.mp.dps = 30


def gauss_integral(n, h):
    return mp.gamma(n + 1) * mp.exp(-h * h / 4) * mp.pcfd(-n - 1, h) / mp.sqrt(2 * mp.pi)


def gauss_integral_quad(n, h):
    phi = lambda s: mp.exp(-s * s / 2) / mp.sqrt(2 * mp.pi)
    return mp.quad(lambda x: x ** n * phi(x + h), mp.linspace(0, 4, 161) + [mp.inf])


n = mp.mpf(5) / 2
for h in (11, 13):
    value = gauss_integral(n, mp.mpf(h))
    check = gauss_integral_quad(n, mp.mpf(h))
    assert abs(value / check - 1) < mp.mpf(10) ** -12, (value, check)
    print("F_{5/2}(%d) = %s" % (h, mp.nstr(value, 20)))
