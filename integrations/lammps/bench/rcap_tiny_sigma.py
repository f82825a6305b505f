"""Where a rough + cap law (E-GW, mu = 4, p_y = 0.01 E*) stops building in a LAMMPS run as
sigma/delta_y falls, and how far its restitution lies from the smooth cap's (Hertz + cap,
the rough model's sigma -> 0 limit) there: stop 49 (lmp15), the threshold below which pair
egw and fix wall/egw take the Hertz + cap table with a WARNING.

For each sigma/delta_y (the contact's sigma over the pair's first-yield overlap) one run of
the head-on glass-bead pair at 2 and 5 v_y (suite_cap.py's rcap deck) with
EGW_CACHE_DIR=off on 1 rank, TOL from the command line, a time limit per run: the wall
time of the run (set-up dominated) and e at each speed against egw_restitution's Hertz +
cap e. Usage: python rcap_tiny_sigma.py TOL LIMIT_S RATIO...
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test"))
os.environ["EGW_CACHE_DIR"] = "off"
os.environ.setdefault("OMP_NUM_THREADS", "1")
from suite_cap import (E, NU, E_STAR, R_STAR, M_STAR, cap_units, cap_reference,  # noqa: E402
                       cap_deck, lmp, result)
import subprocess  # noqa: E402

tol, limit = float(sys.argv[1]), float(sys.argv[2])
ratios = [float(x) for x in sys.argv[3:]]
p_y = 0.01 * E_STAR
vy, dy = cap_units(p_y, R_STAR, M_STAR)
speeds = [2 * vy, 5 * vy]
smooth = [cap_reference(p_y, R_STAR, M_STAR, v) for v in speeds]
dt = 0.5 * min(r[3] for r in smooth)
nrun = int((20 * dt + 2.0 * max(r[2] for r in smooth)) / dt)
print(f"TOL {tol:g}, limit {limit:g} s, RCAP_REACH {os.environ.get('RCAP_REACH', '6')}; smooth cap e at 2, 5 v_y: "
      f"{smooth[0][0]:.6f} {smooth[1][0]:.6f}", flush=True)
for ratio in ratios:
    s_body = ratio * dy / math.sqrt(2)    # the contact's sigma = sqrt(2) s_body
    reach = float(os.environ.get("RCAP_REACH", "6"))
    style = f"egw E-GW {tol!r}" + (f" overlap_max {reach * dy / R_STAR!r}" if reach > 0 else "")
    coeff = f"E {E} nu {NU} sigma {s_body!r} mu 4 flow_pressure {p_y!r}"
    deck = cap_deck(coeff, None, speeds, dt, nrun, style=style)
    t0 = time.perf_counter()
    try:
        rc, out = lmp(deck, _timeout=limit)
    except subprocess.TimeoutExpired:
        print(f"sigma/delta_y {ratio:g}: no result within {limit:g} s", flush=True)
        continue
    wall = time.perf_counter() - t0
    if rc != 0:
        err = [l for l in out.splitlines() if "ERROR" in l or "WARNING" in l]
        print(f"sigma/delta_y {ratio:g}: rc {rc} in {wall:.1f} s: {err[:2]}", flush=True)
        continue
    es = result(out)
    warn = [l for l in out.splitlines() if "WARNING" in l]
    print(f"sigma/delta_y {ratio:g}: {wall:.1f} s; e {es[0]:.6f} {es[1]:.6f}; e - e_smooth "
          f"{es[0] - smooth[0][0]:+.2e} {es[1] - smooth[1][0]:+.2e}"
          + (f"; {warn[0][:160]}" if warn else ""), flush=True)
