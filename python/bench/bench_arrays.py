"""The array calls of the egw package against their references, in one run (issue 24):

    .venv/bin/python python/bench/bench_arrays.py     (from the repository root)

1. egw.hertz over 1e5 overlaps (one C call) against a plain numpy expression of the same
   formula with the same three outputs (force, stiffness, contact radius): goal <= 3x.
2. egw.flat_pressure over 1e5 separations against a C program calling egw_flat_pressure
   once per point (python/bench/c_flat_loop.c, compiled here against the library the
   package loaded): goal <= 2x.
3. 1000 E-GW solves (egw.solve over an array) on 2 threads against 1 thread: goal >= 1.8x
   (each point's solve is single-threaded; the points run in parallel). Needs 2 idle
   cores: on a loaded machine the ratio says so (the load average is printed).
Times are the best of several repeats (solves: of 2)."""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import egw
from egw import _capi

N = 100_000
P_ROUGH = dict(radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)


def best_of(fn, repeats):
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def bench_hertz(repeats=50):
    p = egw.Params(model="Hertz", radius=5e-4, modulus=3.678e10)
    delta = np.linspace(-1e-6, 1e-5, N)
    radius, modulus = p.radius, p.modulus

    def numpy_hertz():
        d = np.maximum(delta, 0.0)
        a = np.sqrt(radius * d)
        return (4.0 / 3.0) * modulus * a * d, 2.0 * modulus * a, a

    f_np, _, _ = numpy_hertz()
    f_egw, _, _ = egw.hertz(p, delta)
    assert np.allclose(f_egw, f_np, rtol=1e-14, atol=0), "values differ"
    # alternate the two sides so that both see the same machine state
    t_np = t_egw = float("inf")
    for _ in range(repeats):
        t_np = min(t_np, best_of(numpy_hertz, 1))
        t_egw = min(t_egw, best_of(lambda: egw.hertz(p, delta), 1))
    return t_egw, t_np


def bench_flat(repeats=20):
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(os.path.dirname(here))
    p = egw.Params(model="E-GW", **P_ROUGH)
    lo, hi = -4e-6, 2e-6
    sep = lo + (hi - lo) * (np.arange(N) + 0.5) / N
    t_py = best_of(lambda: egw.flat_pressure(p, sep), repeats)
    total = egw.flat_pressure(p, sep).sum()
    with tempfile.TemporaryDirectory() as tmp:
        exe = os.path.join(tmp, "c_flat_loop")
        for name in ("libegw.so", "libegw.so.0.3"):
            os.symlink(_capi.lib._name, os.path.join(tmp, name))
        subprocess.run(["cc", "-O2", "-o", exe, os.path.join(here, "c_flat_loop.c"),
                        "-I", os.path.join(repo, "include"), "-L", tmp, "-legw",
                        f"-Wl,-rpath,{tmp}"], check=True)
        args = [str(N), str(repeats), repr(lo), repr(hi)] + [repr(P_ROUGH[k]) for k in
                                                              ("radius", "modulus", "sigma",
                                                               "mu")]
        out = subprocess.run([exe] + args, check=True, capture_output=True,
                             text=True).stdout.split()
    c_ns, c_sum = float(out[0]), float(out[1])
    assert abs(c_sum - total) <= 1e-12 * abs(total), "values differ"
    return 1e9 * t_py / N, c_ns


def bench_solves(n=1000, repeats=2):
    p = egw.Params(model="E-GW", **P_ROUGH)
    delta = np.linspace(-2e-6, 2e-5, n)
    times = {}
    for threads in (1, 2):
        o = egw.Options(n_threads=threads)
        times[threads] = best_of(lambda: egw.solve(p, delta, o), repeats)
    one, two = egw.solve(p, delta, egw.Options(n_threads=1)), egw.solve(
        p, delta, egw.Options(n_threads=2))
    assert np.array_equal(one.force, two.force), "thread count changed the results"
    return times[1], times[2]


def main():
    print(f"egw {egw.version()}, {os.cpu_count()} cpus, load average "
          f"{os.getloadavg()[0]:.2f} before the run")
    t_egw, t_np = bench_hertz()
    print(f"1. hertz, {N} points: egw.hertz {1e3 * t_egw:.3f} ms, numpy expression "
          f"{1e3 * t_np:.3f} ms, ratio {t_egw / t_np:.2f} (goal <= 3)")
    py_ns, c_ns = bench_flat()
    print(f"2. flat_pressure, {N} points: egw.flat_pressure {py_ns:.1f} ns/point, C loop "
          f"{c_ns:.1f} ns/point, ratio {py_ns / c_ns:.2f} (goal <= 2)")
    t1, t2 = bench_solves()
    print(f"3. 1000 E-GW solves: 1 thread {t1:.3f} s, 2 threads {t2:.3f} s, speed-up "
          f"{t1 / t2:.2f} (goal >= 1.8; load average now {os.getloadavg()[0]:.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
