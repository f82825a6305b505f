#!/usr/bin/env python3
"""egw's periodic BEM flat law against ContactMechanics, timed in one run (issue 31).

Makes the seeded self-affine periodic maps of the benchmark (tools/reference/
bem_contactmechanics.py's generator: H = 0.8, unit square, rms slope 0.1, every wave vector
up to the pixel), 512^2 and 576^2, writes them to out/bench/bem_map_<n>.txt (one line per
x index), times ContactMechanics' periodic FFT system (PeriodicFFTElasticHalfSpace, E* = 1,
hard wall, Polonsky-Keer CG) on the 512^2 map for ten loads p/E* geometric from 1e-6 to
1e-2, each warm-started from the previous displacement, with CM's default tolerances (a
user's run) and with a tight one (pentol 1e-8 rms), then runs `egw-bench --bem`
(bem_flat_curve on both maps, p/E* 1e-6 ... 1e-2, 5 loads per decade) and prints the
ratios (egw: best of two runs). Threads: OMP_NUM_THREADS (default 2) for egw; CM's FFTs run in muFFT/numpy as
installed. The machine may be shared: the ratio from one run is what counts. egw's solve
opens about twenty short OpenMP/FFTW parallel regions per CG step, so on an oversubscribed
machine (more runnable threads than cores) a 2-thread run can be many times slower than a
1-thread one (measured 2026-11-28: 10 s quiet, > 170 s with two other busy processes on
2 cores); compare with OMP_NUM_THREADS=1 when the load average is above the core count.

Usage, from the project root (ContactMechanics and SurfaceTopography in .venv):
    .venv/bin/python tools/bench/bem_contactmechanics_time.py [--skip-egw]
"""
import os
import re
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "reference"))
from bem_contactmechanics import self_affine_map  # noqa: E402


def write_map(h, path):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(f"{h.shape[0]} {h.shape[1]} {1.0 / h.shape[0]!r}\n")
        for i in range(h.shape[0]):
            f.write(" ".join(repr(float(v)) for v in h[i, :]) + "\n")
    os.replace(tmp, path)


def time_cm(h, loads, pentol=None):
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import Topography

    n = h.shape[0]
    top = Topography(h, physical_sizes=(1.0, 1.0), periodic=True)
    substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(1.0, 1.0))
    system = NonSmoothContactSystem(substrate, top)
    disp = None
    rows = []
    t0 = time.perf_counter()
    for p in loads:
        kw = {} if pentol is None else {"pentol": pentol}
        res = system.minimize_proxy(external_force=float(p), initial_displacements=disp,
                                    maxiter=100000, **kw)
        if not res.success:
            raise RuntimeError(f"CM: no convergence at p = {p}")
        disp = res.x
        gap = system.compute_gap(res.x, res.offset)
        rows.append((float(p), float(np.mean(gap)),
                     float(system.compute_relative_contact_area()), res.nit))
    return time.perf_counter() - t0, rows


def main():
    os.makedirs("out/bench", exist_ok=True)
    maps = {}
    for n in (512, 576):
        maps[n] = self_affine_map(n, slope=0.1)
        write_map(maps[n], f"out/bench/bem_map_{n}.txt")
    print(f"load average at the start: {os.getloadavg()}")
    h = maps[512]
    rms = float(np.sqrt(np.mean(h ** 2)))
    loads = np.geomspace(1e-6, 1e-2, 10)
    t_default, rows = time_cm(h, loads)
    print(f"ContactMechanics, 512^2, ten warm-started loads 1e-6..1e-2, default tolerances: "
          f"{t_default:.2f} s")
    for p, u, a, it in rows:
        print(f"  p/E* = {p:.3e}  u/rms = {u / rms:.6f}  area = {a:.6e}  iterations {it}")
    t_tight, rows_t = time_cm(h, loads, pentol=1e-8 * rms)
    print(f"ContactMechanics, same, pentol 1e-8 rms: {t_tight:.2f} s")
    if "--skip-egw" in sys.argv:
        return
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "2")
    best = {}
    for _ in range(2):  # best of two egw runs: the machine may be shared
        out = subprocess.run([".venv/bin/fpm", "run", "egw-bench", "--profile", "release",
                              "--", "--bem"], env=env, capture_output=True, text=True,
                             check=True).stdout
        print(out)
        for n, t in re.findall(r"bem_flat_curve (\d+)\^2 .*?([0-9.]+) s", out):
            best[int(n)] = min(best.get(int(n), float("inf")), float(t))
    print(f"load average at the end: {os.getloadavg()}")
    for n, t in sorted(best.items()):
        print(f"egw bem_flat_curve {n}^2, {env['OMP_NUM_THREADS']} threads, best of 2: {t:.2f} s")
    if 512 in best:
        t_egw = best[512]
        print(f"ratio egw (whole law, 21 loads) / CM (ten loads): default tolerances "
              f"{t_egw / t_default:.3f}, pentol 1e-8 rms {t_egw / t_tight:.3f}")

if __name__ == "__main__":
    main()
