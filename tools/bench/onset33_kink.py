#!/usr/bin/env python3
"""Where a rough + cap table's curves are not smooth (doc/benchmarks.md "Stop 67: onset33").

    python3 tools/bench/onset33_kink.py CSV [M_LO M_HI] [--loo S ...]

CSV: an egw-table hysteresis CSV of a rough + cap table (format 6: u on the two-piece map,
README's E-GW + cap with delta_y = 100). Per delta_max node m in [M_LO, M_HI] (delta_y;
default 0.98-1.3), the s in (0.3, 1/2) of the first piece where u's second divided difference
jumps most (its largest ratio to the mean of its two neighbours' on each side: a kink of
the slope du/ds, d2u/ds2 stepping up, between s nodes), that s as an overlap above the knee, delta - k = (m - k)(1 - 2 s)
(the map's first piece, doc/formats.md), and the jump. --loo S: per node the leave-one-out
error at the s node nearest S: u(m_j) minus the cubic in m through m_(j-2), m_(j-1),
m_(j+1), m_(j+2), over max(u, 1e-3) (the weight of the local force goal).
"""
import sys

DELTA_Y = 100.0


def read(path):
    rows, knees = {}, []
    for line in open(path):
        if line.startswith("# knee ="):
            knees.append(float(line.split("=")[1]))
        if line[0] in "#d":
            continue
        f = line.split(",")
        if len(f) < 5:
            continue
        rows.setdefault(float(f[0]), []).append((float(f[2]), float(f[3])))
    ms = sorted(rows)
    s = [r[0] for r in rows[ms[0]]]
    u = [[r[1] for r in rows[m]] for m in ms]
    return ms, knees, s, u


def second_differences(s, u):
    d = {}
    for i in range(1, len(s) - 1):
        left = (u[i] - u[i - 1]) / (s[i] - s[i - 1])
        right = (u[i + 1] - u[i]) / (s[i + 1] - s[i])
        d[i] = (right - left) / (0.5 * (s[i + 1] - s[i - 1]))
    return d


def main():
    args = sys.argv[1:]
    loo = []
    if "--loo" in args:
        k = args.index("--loo")
        loo = [float(a) for a in args[k + 1:]]
        args = args[:k]
    path = args[0]
    lo, hi = (float(args[1]), float(args[2])) if len(args) >= 3 else (0.98, 1.3)
    ms, knees, s, u = read(path)
    print("m/delta_y  knee/sigma  kink s  (delta - knee)/sigma  d2u/ds2 jump")
    for j, m in enumerate(ms):
        if not lo <= m / DELTA_Y <= hi:
            continue
        d = second_differences(s, u[j])
        best, at = 0.0, None
        for i in d:
            if not 0.3 < s[i] < 0.5 or i - 2 not in d or i + 2 not in d:
                continue
            around = 0.25 * (abs(d[i - 2]) + abs(d[i - 1]) + abs(d[i + 1]) + abs(d[i + 2]))
            ratio = abs(d[i]) / max(around, 1e-300)
            if ratio > best:
                best, at = ratio, i
        if at is None:
            continue
        k = knees[j]
        print("%.5f  %.4e  %.5f  %.4e  %.2f" % (m / DELTA_Y, k, s[at], (m - k) * (1 - 2 * s[at]),
                                                 best))
    for target in loo:
        i = min(range(len(s)), key=lambda q: abs(s[q] - target))
        print("leave-one-out at s = %.5f (weighted by 1/max(u, 1e-3)), m/delta_y: error" % s[i])
        x = [m / DELTA_Y for m in ms]
        out = []
        for j in range(2, len(ms) - 2):
            if not lo <= x[j] <= hi:
                continue
            idx = [j - 2, j - 1, j + 1, j + 2]
            w = []
            for a in idx:
                v = 1.0
                for b in idx:
                    if b != a:
                        v *= (x[j] - x[b]) / (x[a] - x[b])
                w.append(v)
            e = u[j][i] - sum(wk * u[a][i] for wk, a in zip(w, idx))
            out.append("%.4f:%+.1e" % (x[j], e / max(u[j][i], 1e-3)))
        for q in range(0, len(out), 8):
            print("  " + "  ".join(out[q:q + 8]))


if __name__ == "__main__":
    main()
