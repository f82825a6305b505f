#!/usr/bin/env python3
"""e of the smooth sphere with the cap far above v_y, from tools/reference/cap_reference.py
(independent of egw; stop 57, capreach): its loading work to c0 = 14 a_y from its Chebyshev
loading curve (as its own restitution rows), beyond c0 the fully capped closed form (P/P_y =
3c^2/2, Delta = c^2/2 + 8c/pi^2: cap_reference.load_at_c's limit, the elastic ring thinner than
1e-9 c from ~20 delta_y on), the unloading work from its Loaded.unload_work, Richardson over
m, 2m, 4m ring elements. Universal units (theory.md section 12): v in v_y.

Run: python tools/reference/cap_restitution_fast.py [M] [V/V_Y ...]
     (default M = 20, V/V_Y = 100 300 760 1000; ~1 min a speed on one core)
"""
import os
import sys

import numpy as np
from scipy.optimize import brentq

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cap_reference as cr  # noqa: E402

C0 = 14.0
K = 8 / np.pi**2


def main():
    m0 = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    vs = [float(v) for v in sys.argv[2:]] or [100.0, 300.0, 760.0, 1000.0]
    es = {v: [] for v in vs}
    for m in (m0, 2 * m0, 4 * m0):
        curve = cr.load_curve(m, C0)
        w0 = cr.load_work(curve, C0)

        def work(c):
            if c <= C0:
                return cr.load_work(curve, c)
            capped = lambda s: 1.5 * (s**4 / 4 + K * s**3 / 3)    # int 3c^2/2 dDelta/dc dc
            return w0 + capped(c) - capped(C0)

        for v in vs:
            c = brentq(lambda cc: work(cc) - 0.4 * v * v, 1e-6, 400.0, xtol=1e-14)
            ld = cr.Loaded(c, m)
            es[v].append(np.sqrt(ld.unload_work() / work(c)))
            print(f"m {m} v/v_y {v:g}: c {c:.6f} delta_m {ld.dm:.6f} e {es[v][-1]:.10f}",
                  file=sys.stderr, flush=True)
    for v in vs:
        ext, err, order = cr.richardson(es[v])
        print(f"v/v_y {v:g}: e {ext:.10f} error {err:.2e} order {order:.3g}")


if __name__ == "__main__":
    main()
