"""Hertz's contact duration above 1 % of the peak force, by mpmath, against egw.time_step.

The force P = (4/3) E* sqrt(R) d^1.5 exceeds 1 % of its peak where d > 0.01^(2/3) d_m; with
d = d_m (1 - s^2) the time from there to the turning point is
  t = int_0^s1 2 s d_m / (v sqrt(1 - (1 - s^2)^2.5)) ds,
regular at s = 0 (written with expm1/log1p). The duration is twice that (Hertz is
reversible). doc/theory.md section 10 quotes egw's relative error (audit25: -9.48e-5 at
every speed: the 16-point rule's, Hertz being self-similar; stop 60, tstep26: -1.3e-11,
the adaptive panels; the closed form is in tools/reference/duration_reference.py).

    PYTHONPATH=<mpmath> .venv/bin/python tools/reference/hertz_duration_ref.py
"""
import mpmath as mp
import egw

mp.mp.dps = 30
R, E, m = 1e-3, 1e11, 1e-5
p = egw.Params(model="Hertz", radius=R, modulus=E)
for v in (1e-3, 0.05, 5.0):
    dm = (mp.mpf(15) * m * v**2 / (16 * E * mp.sqrt(R)))**(mp.mpf(2) / 5)
    s1 = mp.sqrt(1 - mp.mpf("0.01")**(mp.mpf(2) / 3))
    f = lambda s: 2 * s * dm / (v * mp.sqrt(-mp.expm1(mp.mpf(2.5) * mp.log1p(-s**2))))
    exact = 2 * mp.quad(f, [0, s1])
    got = egw.time_step(p, mass=m, velocity=v, tolerance=1e-3).duration
    print(f"v = {v:g} m/s: duration exact {mp.nstr(exact, 15)} egw {got:.15g} "
          f"rel {float(got / exact - 1):.3e}")
