#!/usr/bin/env python3
"""Where a rough + cap hysteresis build's curve CPU goes, from the SOLVE lines that
tools/bench/curve28_solve_probe.patch prints (doc/benchmarks.md, "Stop 62: curve28").

usage: EGW_PROBE_LOG=1 OMP_NUM_THREADS=1 egw-table ... 2> LOG >/dev/null
       curve28_solve_log.py LOG

A SOLVE line: phase (0 first curves, 2 check curves, 3 promoted check curves'
bisection, 4 uncleared check nodes), piece of the two-piece map (1: s < 1/2, down to the
knee; 2: knee to delta = 0; 3: the tail; 0: a curve's loading history), delta_max, m -
delta, |delta - delta of the solve it started from| (-1: none), its thread CPU [s],
refine_m's pass. Prints the solves and CPU per phase and piece, per delta_max band, per
start distance, and each parallel region's 2-thread makespan as OpenMP's dynamic
schedule runs it (largest delta_max first) from these one-thread costs.
"""
import collections
import sys

import numpy as np


def main():
    rows = [l.split() for l in open(sys.argv[1]) if l.startswith("SOLVE")]
    ph = np.array([int(r[1]) for r in rows])
    pc = np.array([int(r[2]) for r in rows])
    m = np.array([float(r[3]) for r in rows])
    d = np.array([float(r[5]) for r in rows])
    t = np.array([float(r[6]) for r in rows])
    ps = np.array([int(r[7]) for r in rows])
    print(f"records {len(t)} (unloading solves {np.sum(pc > 0)}), thread CPU {t.sum():.3f} s")
    print("phase piece: solves, CPU s, mean ms")
    for f in (0, 2, 3, 4):
        for p in (0, 1, 2, 3):
            q = (ph == f) & (pc == p)
            if q.any():
                print(f"  {f} {p}: {q.sum():5d} {t[q].sum():7.3f} {1e3 * t[q].mean():6.2f}")
    print("delta_max band: histories | piece 1 | piece 2 | piece 3 (n, mean ms), CPU s")
    edges = [0, 100, 150, 200, 300, 400, 500, np.inf]
    for lo, hi in zip(edges[:-1], edges[1:]):
        s = (m >= lo) & (m < hi)
        cells = []
        for p in (0, 1, 2, 3):
            q = s & (pc == p)
            cells.append(f"{q.sum():4d} {1e3 * t[q].mean() if q.any() else 0:5.2f}")
        print(f"  [{lo:g}, {hi:g}): " + " | ".join(cells) + f" | {t[s].sum():.3f}")
    print("start distance |delta - delta_start|/delta_max, unloading solves of piece 1:")
    rel = np.where(d < 0, np.inf, d / np.maximum(m, 1e-300))
    for lo, hi in [(0, 0.01), (0.01, 0.03), (0.03, 0.1), (0.1, 0.3), (0.3, np.inf)]:
        q = (pc == 1) & (rel >= lo) & (rel < hi)
        if q.any():
            print(f"  [{lo:g}, {hi:g}): {q.sum():4d} mean {1e3 * t[q].mean():.2f} ms, "
                  f"median {1e3 * np.median(t[q]):.2f} ms, CPU {t[q].sum():.3f} s")
    regions = collections.OrderedDict()
    for f, p, mm, tt in zip(ph, ps, m, t):
        regions.setdefault((p, f), collections.defaultdict(float))[mm] += tt
    total = span = 0.0
    for (p, f), curves in regions.items():
        costs = [curves[k] for k in sorted(curves, reverse=True)]
        threads = [0.0, 0.0]
        for c in costs:
            threads[threads.index(min(threads))] += c
        total += sum(costs)
        span += max(threads)
    print(f"2 threads: makespan {span:.3f} s of {total:.3f} s CPU (CPU/makespan "
          f"{total / span:.3f}) over {len(regions)} parallel regions")


if __name__ == "__main__":
    main()
