"""Cost per point of a table evaluated over a numpy array from Python (one C call per
array) against a C program calling egw_table_eval once per point, in one run.

    .venv/bin/python python/bench/bench_eval.py     (from the repository root)

Builds an E-GW table (default egw-table scene's pair), writes it, compiles c_loop.c against
the library the egw package loaded, and prints ns per point for both and their ratio
(goal: Python/C <= 2). Best of several repeats on each side."""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import egw
from egw import _capi

N, REPEATS = 1_000_000, 15


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(os.path.dirname(here))
    lib = _capi.lib._name
    p = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)
    lo, hi = -2e-6, 2e-5
    table = egw.Table.build(p, lo, hi, rel_tol=1e-6)
    delta = lo + (hi - lo) * (np.arange(N) + 0.5) / N
    best = float("inf")
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        force, stiffness = table.eval(delta)
        best = min(best, time.perf_counter() - t0)
    py_ns = 1e9 * best / N
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "t.bin")
        table.write(path, "binary")
        exe = os.path.join(tmp, "c_loop")
        # link the very library Python loaded, under the names the linker and the loader
        # look for (the bundled file keeps the SONAME libegw.so.0.3 of the CMake build)
        for name in ("libegw.so", "libegw.so.0.3"):
            os.symlink(lib, os.path.join(tmp, name))
        subprocess.run(["cc", "-O2", "-o", exe, os.path.join(here, "c_loop.c"),
                        "-I", os.path.join(repo, "include"), "-L", tmp, "-legw",
                        f"-Wl,-rpath,{tmp}"], check=True)
        out = subprocess.run([exe, path, str(N), str(REPEATS), repr(lo), repr(hi)],
                             check=True, capture_output=True, text=True).stdout.split()
    c_ns, c_sum = float(out[0]), float(out[1])
    assert abs(c_sum / REPEATS - force.sum()) <= 1e-9 * abs(c_sum / REPEATS), "values differ"
    print(f"table eval, {N} points, best of {REPEATS}:")
    print(f"  C loop (egw_table_eval per point)        {c_ns:7.2f} ns/point")
    print(f"  Python Table.eval(numpy array), 1 call    {py_ns:7.2f} ns/point")
    print(f"  ratio Python/C                            {py_ns / c_ns:7.2f}  (goal <= 2)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
