#!/usr/bin/env python3
"""Error bands of a rough_cap_local_decompose run, split at m = 1.3 delta_y (stop 66,
umap33; doc/benchmarks.md "Stop 66: umap33").

Reads the "pt" lines (kind, m/delta_y, delta/delta_y, P_ref/P(m), hist, tab, tot) of
tools/bench/rough_cap_local_decompose.f90's output (a run or a REPLAY of refs), pools
midpoints and nodes (a replayed grid's nodes need not be the references' turning
points), and prints per P_ref/P(m) band the worst tot for m < 1.3 delta_y and for
m >= 1.3 delta_y, and how many lowest-band points exceed 1e-4:

    python3 tools/bench/umap33_bands.py RUN.txt [RUN2.txt ...]
"""
import sys

BANDS = [(0.1, 1.0), (0.01, 0.1), (0.003, 0.01), (0.0, 0.003)]


def bands(path):
    worst = {(b, side): 0.0 for b in range(4) for side in (0, 1)}
    over = [0, 0]
    count = [0, 0]
    for line in open(path):
        f = line.split()
        if len(f) != 8 or f[0] != "pt":
            continue
        m, frac, tot = float(f[2]), float(f[4]), float(f[7])
        side = 0 if m < 1.3 else 1
        for b, (lo, hi) in enumerate(BANDS):
            if lo <= frac < hi:
                worst[(b, side)] = max(worst[(b, side)], tot)
                if b == 3:
                    count[side] += 1
                    if tot > 1e-4:
                        over[side] += 1
    return worst, over, count


for path in sys.argv[1:]:
    worst, over, count = bands(path)
    cells = [f"{worst[(b, 0)]:.1e} | {worst[(b, 1)]:.1e}" for b in range(4)]
    print(f"{path}: " + " ; ".join(cells) +
          f" ({over[0]} of {count[0]} | {over[1]} of {count[1]} lowest-band > 1e-4)")
