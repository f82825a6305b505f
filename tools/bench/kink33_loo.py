#!/usr/bin/env python3
"""Leave-one-out errors in delta_max of today's map and of a map broken at the annulus
(doc/benchmarks.md "Stop 67: kink33"; the data from tools/bench/kink33_break_loo.f90).

    python3 tools/bench/kink33_loo.py LOO_OUT [STRIDE ...]

Per map (old: today's first piece; new: the first piece split at delta_b = max(delta_open,
knee), its 24 points on [delta_b, m] and 6 on [knee, delta_b]) and per stride q (every q-th
of the input's m nodes, default 1 2 4 8), at each fixed s the error of u(m_j) against the
cubic in m through m_(j-2q), m_(j-q), m_(j+q), m_(j+2q), over max(u, 1e-3) (the weight of
the local force goal, as onset33_kink.py --loo): the worst per band of m/delta_y, and at
which s index (0-23 above delta_b, 24-29 below it in "new").
"""
import sys

BANDS = [(1.0, 1.018), (1.018, 1.03), (1.03, 1.06), (1.06, 1.1), (1.1, 1.2)]


def lagrange(xs, ys, x):
    total = 0.0
    for i, (xi, yi) in enumerate(zip(xs, ys)):
        w = 1.0
        for j, xj in enumerate(xs):
            if j != i:
                w *= (x - xj) / (xi - xj)
        total += w * yi
    return total


def main():
    path = sys.argv[1]
    strides = [int(a) for a in sys.argv[2:]] or [1, 2, 4, 8]
    rows = []
    for line in open(path):
        if line.startswith("#"):
            continue
        v = [float(x) for x in line.split()]
        rows.append(v)
    ms = [r[0] for r in rows]
    maps = {"old": [r[4:28] for r in rows], "new": [r[28:58] for r in rows],
            "new above delta_b": [r[28:52] for r in rows],
            "new below delta_b": [r[52:58] for r in rows]}
    print("m nodes %d in [%.5f, %.5f]; delta_open - knee > 0 from m = %s" % (
        len(ms), ms[0], ms[-1],
        next(("%.5f" % r[0] for r in rows if r[2] > r[1]), "none")))
    print("stride  map                " + "  ".join("[%.3f,%.3f)" % b for b in BANDS))
    for q in strides:
        for name, u in maps.items():
            worst = [(0.0, None)] * len(BANDS)
            for j in range(0, len(ms)):
                if j % q:
                    continue
                idx = [j - 2 * q, j - q, j + q, j + 2 * q]
                if idx[0] < 0 or idx[-1] >= len(ms):
                    continue
                b = next((k for k, (lo, hi) in enumerate(BANDS) if lo <= ms[j] < hi), None)
                if b is None:
                    continue
                for i in range(len(u[j])):
                    ys = [u[k][i] for k in idx]
                    if min(ys + [u[j][i]]) < 0:
                        continue   # (a failed solve)
                    e = abs(u[j][i] - lagrange([ms[k] for k in idx], ys, ms[j])) / max(
                        u[j][i], 1e-3)
                    if e > worst[b][0]:
                        worst[b] = (e, i)
            print("%6d  %-17s  " % (q, name) + "  ".join(
                "%8.1e (%2s)" % (e, "-" if i is None else i) for e, i in worst))


if __name__ == "__main__":
    main()
