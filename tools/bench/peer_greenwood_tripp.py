#!/usr/bin/env python3
"""Peer comparison (issue 5 item 2): the Greenwood-Tripp reference solution of the Python
package ContactMechanics (module ContactMechanics.ReferenceSolutions.GreenwoodTripp,
function GreenwoodTripp) against egw's classic-GW solver on the same problems.

Run from the project root, after `fpm build --profile release`:
    python3 tools/bench/peer_greenwood_tripp.py            # -> doc/bench/peer.csv
    python3 tools/bench/peer_greenwood_tripp.py --quick    # two cases only

ContactMechanics is a benchmark dependency only; this script installs it with pip if it
is missing (and numpy/scipy with it).

Mapping of the peer's nondimensional variables to egw's (read from the peer's source;
Greenwood & Tripp 1967 notation):
  * mu is the same parameter: mu = (8/3) eta sigma sqrt(2 B beta) with B the sphere
    radius, i.e. egw's params%mu with R = B.
  * Radii: rho = r / sqrt(2 R sigma); egw's scaled radius is r / sqrt(R sigma) = sqrt(2) rho.
  * Pressure: p_peer = p / (E* sqrt(sigma / (8 R))) and the peer sets p_peer = mu F_{3/2}(gap
    / sigma); egw's p_G = C sigma^{3/2} F_{3/2} with C = mu E*/(2 sigma sqrt(2R)) is the same
    law, mu E* sqrt(sigma/(8R)) F_{3/2}.
  * Deflection: w in units of sigma; the peer's w0 = int p_peer drho is the central
    deflection u(0) = (2/E*) int p dr in units of sigma (checked: (2/E*) E* sqrt(sigma/8R)
    sqrt(2 R sigma) = sigma).
  * The peer's input d is the CENTRAL GAP d* = gap(0)/sigma (its gap is d + rho^2 + w - w0),
    not the rigid-body approach. With egw's gap r^2/(2R) - delta + u(r) the approach is
    delta/sigma = w0 - d*. So every peer run is mapped to egw's delta/sigma = w0 - d*,
    with w0 = Simpson(p, rho) recomputed from the returned pressure.
  * Force: P = int 2 pi r p dr = sqrt(2) pi E* sqrt(R) sigma^{3/2} int rho p_peer drho, so
    P_scaled = P / (E* sqrt(R) sigma^{3/2}) = sqrt(2) pi Simpson(rho p_peer, rho).
Error of both against egw's solve at rel_tol = 1e-9 at the same delta/sigma (that solver is
checked against the independent references of test/data/sphere_reference.csv to ~1e-9,
see doc/benchmarks.md). The peer's error includes that of its w0 (an error in the mapped
delta counts as a force error: that is what a user of either code gets).
Peer settings: its defaults (n = 100 grid points, tol = 1e-6, mix = 0.1), and n = 200,
rhomax = max(5, 2 sqrt(max(delta, 1)/2) + 3) in units of sqrt(2 R sigma), so the
truncation radius lies well beyond the Hertz radius sqrt(delta R) (rho_H = sqrt(delta/2)).
"""
import csv
import os
import subprocess
import sys
import time


def ensure(module, package):
    try:
        __import__(module)
    except ImportError:
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", package])


ensure("numpy", "numpy")
ensure("scipy", "scipy")
ensure("ContactMechanics", "ContactMechanics")

import numpy as np  # noqa: E402
from scipy.integrate import simpson  # noqa: E402
from ContactMechanics.ReferenceSolutions.GreenwoodTripp import GreenwoodTripp  # noqa: E402

# (central gap d*, mu): chosen so the mapped delta/sigma spans separated to deep contact
CASES = [(2.0, 1.0), (0.0, 1.0), (-1.0, 1.0), (-3.0, 1.0), (1.0, 10.0), (0.0, 10.0),
         (-1.0, 10.0), (0.0, 0.3)]
QUICK = [(0.0, 1.0), (0.0, 10.0)]


def run_peer(d_star, mu, n):
    rhomax = 5.0
    t0 = time.perf_counter()
    # first pass at the default radius tells the approach; widen if the contact is large
    w, p, rho = GreenwoodTripp(d_star, mu, rhomax=rhomax, n=n)
    w0 = simpson(p, x=rho)
    delta = w0 - d_star
    need = 2.0 * np.sqrt(max(delta, 1.0) / 2.0) + 3.0
    if need > rhomax:
        rhomax = need
        w, p, rho = GreenwoodTripp(d_star, mu, rhomax=rhomax, n=n)
        w0 = simpson(p, x=rho)
        delta = w0 - d_star
    elapsed = time.perf_counter() - t0
    force = np.sqrt(2.0) * np.pi * simpson(rho * p, x=rho)
    return float(delta), float(force), elapsed, rhomax


def main():
    quick = "--quick" in sys.argv
    cases = QUICK if quick else CASES
    rows = []
    for d_star, mu in cases:
        for n in (100, 200):
            delta, force, elapsed, rhomax = run_peer(d_star, mu, n)
            rows.append(dict(d_star=d_star, mu=mu, n=n, rhomax=rhomax, delta=delta,
                             peer_P=force, peer_time_s=elapsed))
            print(f"peer d*={d_star:5.2f} mu={mu:5.2f} n={n}: delta/sigma={delta:.6f} "
                  f"P={force:.8g} in {elapsed:.2f} s", flush=True)
    os.makedirs("doc/bench", exist_ok=True)
    case_file = "doc/bench/peer_cases.txt"
    with open(case_file, "w") as f:
        for r in rows:
            f.write(f"{r['delta']!r} {r['mu']!r}\n")
    fpm = os.path.join(".venv", "bin", "fpm") if os.path.exists(".venv/bin/fpm") else "fpm"
    subprocess.check_call([fpm, "run", "egw-bench", "--profile", "release", "--",
                           "--update-docs", "--peer", case_file])
    with open("doc/bench/peer_egw.csv") as f:
        egw = list(csv.DictReader(f))
    out = "doc/bench/peer.csv"
    with open(out, "w", newline="") as f:
        fields = ["d_star", "mu", "delta_over_sigma", "peer_n", "peer_rhomax", "peer_time_s",
                  "peer_P", "peer_rel_err", "egw_time_s", "egw_P", "egw_rel_err",
                  "egw_est_rel_err", "egw_status", "P_ref", "time_ratio_peer_over_egw"]
        wr = csv.writer(f)
        wr.writerow(fields)
        for r, e in zip(rows, egw):
            pref = float(e["P_ref"])
            egw_p = float(e["P_scaled"])
            wr.writerow([r["d_star"], r["mu"], repr(r["delta"]), r["n"], r["rhomax"],
                         f"{r['peer_time_s']:.4e}", repr(r["peer_P"]),
                         f"{abs(r['peer_P'] / pref - 1):.3e}", e["time_s"], e["P_scaled"],
                         f"{abs(egw_p / pref - 1):.3e}", e["est_rel_err"], e["status"],
                         e["P_ref"], f"{r['peer_time_s'] / float(e['time_s']):.3e}"])
    print("wrote", out)


if __name__ == "__main__":
    main()
