"""Reference values for test/test_rough_sphere.f90 (far-apart rigid limit).

F_n(h) = int_h^inf (s - h)^n phi(s) ds by mpmath quadrature at 30 digits; the output
is pasted into test/ref_rough_sphere.f90. Run: python3 tools/reference/rough_sphere_refs.py
"""
try:
    import mpmath as mp
except ImportError:  # pragma: no cover
    import subprocess, sys
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mpmath"])
    import mpmath as mp

mp.mp.dps = 30


def gauss_integral(n, h):
    phi = lambda s: mp.exp(-s * s / 2) / mp.sqrt(2 * mp.pi)
    return mp.quad(lambda x: x ** n * phi(x + h), [0, 1, 4, mp.inf])


for h in (11, 13):
    print("F_{5/2}(%d) = %s" % (h, mp.nstr(gauss_integral(mp.mpf(5) / 2, mp.mpf(h)), 20)))
