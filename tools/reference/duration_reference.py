"""References for egw_time_step's contact duration (doc/theory.md section 10).

The duration is the time the force spends above 1 % of its peak P_m = P(delta_m), loading
and unloading: t = int dx/v(x) from the onset x_1 (P(x_1) = P_m/100) to delta_m, with
v(x)**2 = (2/m*) int_x^{delta_m} P (the speed vanishes at the turning point delta_m).

1. Hertz, exact (mpmath, 40 digits). P = K d**1.5, K = (4/3) E* sqrt(R), so
   int_x^{d_m} P = (2K/5)(d_m**2.5 - x**2.5) and m* v0**2/2 = (2K/5) d_m**2.5 give
   v(x) = v0 sqrt(1 - (x/d_m)**2.5). With z = (x/d_m)**2.5, dx = (2/5) d_m z**(-3/5) dz:
     t_half = (2 d_m/(5 v0)) int_{z_1}^1 z**(-3/5) (1 - z)**(-1/2) dz
            = (2 d_m/(5 v0)) [B(2/5, 1/2) - B(z_1; 2/5, 1/2)],
   z_1 = (x_1/d_m)**2.5 = 0.01**(5/3) (P(x_1)/P_m = (x_1/d_m)**1.5 = 0.01). Hertz is
   reversible, so duration = 2 t_half = C_H d_m/v0 with
     C_H = (4/5) int_{0.01**(5/3)}^1 z**(-3/5) (1 - z)**(-1/2) dz (mpmath.betainc),
   checked here against the direct quadrature of tools/reference/hertz_duration_ref.py
   (d = d_m (1 - s**2)). d_m = (15 m* v0**2/(16 E* sqrt(R)))**(2/5).

2. Other models, brute force from egw's own forces (egw.solve, egw.solve_unload,
   egw.restitution's delta_m): independent of egw's quadrature (an adaptive Runge-Kutta,
   scipy's DOP853, on dW/du = 2u P(delta_m - u**2), dt/du = 2u/sqrt(2W/m*) written with
   W = u**2 Q, u from 0 to sqrt(delta_m - x_1), x_1 by brentq to 1e-15 of delta_m; Hertz
   checks it, below), NOT of the forces: it checks
   the quadrature, not the solver. P_m is egw.solve_unload at delta_m (the history's loading
   solve at delta_m, as egw_time_step's). Each value at rtol 1e-9 and 1e-10; their
   difference is printed as the reference's own error (tighter rtol only meets the
   forces' own noise, ~1e-9 of P for the cap's solves, and takes hours). The cases up to
   EP-GW slow take ~10 min of CPU. The cap's own accuracy (~3e-6 against
   tools/reference/cap_reference.py, doc/theory.md 12) bounds its duration's.

3. EP-GW + cap (--rough-cap; stop 61): the same integration, each half on its own, the
   solves memoised. Its unloading solves accept relative to a force floor (est_rel_err
   1e-7 .. 5e-7) and that noise stalls DOP853 below rtol ~1e-8 (rtol 1e-8 on the
   unloading did not finish in 10 min); so the loading half at rtol 1e-8, the unloading
   half at 3e-8, each against rtol 1e-7 as its own error. ~2 min of CPU.

    PYTHONPATH=<mpmath, scipy> .venv/bin/python tools/reference/duration_reference.py
    PYTHONPATH=<mpmath, scipy> .venv/bin/python tools/reference/duration_reference.py --rough-cap

4. E-GW and EP-GW (psi 2) without the cap at 1 m/s (--near-contact; stop 62): the
   deepest overlap 1.27 and 1.43 sigma, so that both halves cross delta = 0, where the
   Hertz part's (delta)**(3/2) sets in (rough_breaks' break). As 2., rtol 1e-9 and 1e-10.

    PYTHONPATH=<mpmath, scipy> .venv/bin/python tools/reference/duration_reference.py --near-contact
"""
import math
import sys

import mpmath as mp


def hertz_constant():
    """C_H = duration v0/d_m for Hertz, by the incomplete Beta function and directly."""
    mp.mp.dps = 40
    z1 = mp.mpf("0.01")**(mp.mpf(5) / 3)
    c_beta = mp.mpf(4) / 5 * mp.betainc(mp.mpf(2) / 5, mp.mpf(1) / 2, z1, 1)
    s1 = mp.sqrt(1 - mp.mpf("0.01")**(mp.mpf(2) / 3))
    f = lambda s: 2 * s / mp.sqrt(-mp.expm1(mp.mpf(2.5) * mp.log1p(-s**2)))
    c_direct = 2 * mp.quad(f, [0, s1])
    return c_beta, c_direct


# The cases of test_cap_hysteresis "contact duration against a brute-force quadrature":
# R, E*, m* of a 1 mm glass bead pair; sigma 1 um, mu 4; p_y 1 GPa.
RADIUS, MODULUS, MASS, SIGMA, MU, PSI, P_Y = 5e-4, 4e10, 6.5e-6, 1e-6, 4.0, 2.0, 1e9
CASES = [  # (name, model, flow_pressure, velocity)
    ("Hertz", "Hertz", 0.0, 1.0),
    ("Hertz + cap", "Hertz", P_Y, 1.0),
    ("GW", "GW", 0.0, 0.01),
    ("E-GW", "E-GW", 0.0, 0.01),
    ("EP-GW", "EP-GW", 0.0, 0.01),
    ("EP-GW slow", "EP-GW", 0.0, 1e-4),
    ("EP-GW + cap", "EP-GW", P_Y, 1.0),
]


def brute_duration(params, mass, velocity, rtol, halves=(False, True)):
    """delta_m and the time of the halves (loading: False, unloading: True) summed."""
    import functools
    import egw
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq
    dm = egw.restitution(params, mass=mass, velocity=velocity).max_overlap
    p_m = egw.solve_unload(params, dm, dm).force
    total = 0.0
    for unloading in halves:
        @functools.lru_cache(maxsize=None)
        def force(x, unloading=unloading):
            return (egw.solve_unload(params, x, dm) if unloading else egw.solve(params, x)).force
        target = 0.01 * p_m
        width = dm * 0.05 if dm > 0 else SIGMA
        while force(dm - width) > target:
            width *= 2
        x1 = brentq(lambda x: force(x) - target, dm - width, dm, xtol=1e-15 * abs(dm) + 1e-300,
                    rtol=1e-15)
        # scaled: s = u/u1, f = P/P_m, W = s**2 Q(s) in P_m u1**2 (Q(0) = 1, the mean of f
        # weighted by 2s: dQ/ds = 2 (f - Q)/s, 0 at s = 0 as f is even in s), t in
        # u1 sqrt(m*/P_m) with dt/ds = 2s/sqrt(2W) = sqrt(2/Q): no singular step at s = 0
        u1 = math.sqrt(dm - x1)

        def rhs(s, y):
            f = force(dm - (s * u1)**2) / p_m
            return [0.0 if s == 0 else 2 * (f - y[0]) / s, math.sqrt(2 / y[0])]
        sol = solve_ivp(rhs, (0.0, 1.0), [1.0, 0.0], method="DOP853", rtol=rtol,
                        atol=[1e-3 * rtol, 1e-3 * rtol])
        total += sol.y[1, -1] * u1 * math.sqrt(mass / p_m)
    return dm, total


def rough_cap():
    """EP-GW + cap at 1 m/s (test_cap_hysteresis "contact duration: EP-GW + cap")."""
    import egw
    name, model, p_y, v = CASES[-1]
    params = egw.Params(model=model, radius=RADIUS, modulus=MODULUS, flow_pressure=p_y,
                        sigma=SIGMA, mu=MU, psi=PSI)
    total = 0.0
    for unloading, rtol in ((False, 1e-8), (True, 3e-8)):
        _, coarse = brute_duration(params, MASS, v, 1e-7, (unloading,))
        dm, fine = brute_duration(params, MASS, v, rtol, (unloading,))
        print(f"{name} v = {v:g} {'unloading' if unloading else 'loading'} half "
              f"(rtol {rtol:g}): {fine:.15e}, rtol 1e-7 {coarse - fine:+.2e}", flush=True)
        total += fine
    got = egw.time_step(params, mass=MASS, velocity=v, tolerance=1e-3).duration
    print(f"{name:12s} v = {v:g}: delta_m = {dm:.6e}, duration {total:.15e}; "
          f"egw_time_step {got / total - 1:+.2e}", flush=True)


def near_contact():
    """E-GW and EP-GW (psi 2) without the cap at 1 m/s, delta_m = 1.27 and 1.43 sigma: both
    halves pass delta = 0, where the Hertz part sets in (test_cap_hysteresis "contact
    duration: E-GW, EP-GW turning a sigma into contact"; stop 62)."""
    import egw
    for name, model, psi in (("E-GW", "E-GW", 0.0), ("EP-GW", "EP-GW", PSI)):
        params = egw.Params(model=model, radius=RADIUS, modulus=MODULUS, sigma=SIGMA, mu=MU,
                            psi=psi)
        dm, coarse = brute_duration(params, MASS, 1.0, 1e-9)
        _, fine = brute_duration(params, MASS, 1.0, 1e-10)
        got = egw.time_step(params, mass=MASS, velocity=1.0, tolerance=1e-3).duration
        print(f"{name:12s} v = 1: delta_m = {dm / SIGMA:.4f} sigma, duration {fine:.15e} "
              f"(rtol 1e-9 {coarse / fine - 1:+.1e}); egw_time_step {got / fine - 1:+.2e}",
              flush=True)


def main():
    if "--rough-cap" in sys.argv:
        rough_cap()
        return
    if "--near-contact" in sys.argv:
        near_contact()
        return
    c_beta, c_direct = hertz_constant()
    print(f"Hertz: duration v0/delta_m = {mp.nstr(c_beta, 22)} (incomplete Beta), "
          f"{mp.nstr(c_direct, 22)} (direct), difference {mp.nstr(c_beta - c_direct, 3)}")
    if "--hertz-only" in sys.argv:
        return
    import egw
    for name, model, p_y, v in CASES[:-1]:
        kw = dict(model=model, radius=RADIUS, modulus=MODULUS, flow_pressure=p_y)
        if model != "Hertz":
            kw.update(sigma=SIGMA, mu=MU)
        if model == "EP-GW":
            kw.update(psi=PSI)
        params = egw.Params(**kw)
        dm, coarse = brute_duration(params, MASS, v, 1e-9)
        _, fine = brute_duration(params, MASS, v, 1e-10)
        got = egw.time_step(params, mass=MASS, velocity=v, tolerance=1e-3).duration
        print(f"{name:12s} v = {v:g}: delta_m = {dm:.6e}, duration {fine:.15e} "
              f"(rtol 1e-9: {coarse / fine - 1:+.1e}); egw_time_step {got / fine - 1:+.2e}",
              flush=True)


if __name__ == "__main__":
    main()
