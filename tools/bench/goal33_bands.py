#!/usr/bin/env python3
"""Band table of a rough_cap_local_decompose replay (doc/benchmarks.md "Stop 66: goal33").

    python3 tools/bench/goal33_bands.py OUT [OUT ...] [--worst N]

OUT: the probe's output (any EGW_PROBE_MODEL; its "pt" lines: kind, m/delta_y, delta/delta_y, P_ref/P(m),
hist, tab, tot). Per band of P_ref/P(m) the worst tot (error / max(P_ref, 1e-3 P(m))),
midpoints and nodes pooled, for m < 1.3 delta_y | m >= 1.3 delta_y, and in the lowest
band how many points exceed 1e-4 (as local31's table). --worst N: the N worst points of
the lowest band with m >= 1.3 delta_y.
"""
import sys

BANDS = [(0.1, 1.01), (0.01, 0.1), (0.003, 0.01), (0.0, 0.003)]


def table(path, n_worst):
    head = ""
    pts = []
    for line in open(path):
        if " + cap, rel_tol" in line and not line.startswith("pt "):
            head = line.split(":", 1)[1].strip()
        if not line.startswith("pt "):
            continue
        f = line.split()
        pts.append((f[1], float(f[2]), float(f[3]), float(f[4]), float(f[7])))
    cells = []
    for lo, hi in BANDS:
        cell = []
        for low_m in (True, False):
            sel = [p for p in pts if lo <= p[3] < hi and (p[1] < 1.3) == low_m]
            cell.append(max((p[4] for p in sel), default=0.0))
        cells.append("%.1e \\| %.1e" % tuple(cell))
    low = [p for p in pts if p[3] < 0.003]
    n_lo = sum(1 for p in low if p[1] < 1.3 and p[4] > 1e-4)
    n_hi = sum(1 for p in low if p[1] >= 1.3 and p[4] > 1e-4)
    t_lo = sum(1 for p in low if p[1] < 1.3)
    t_hi = sum(1 for p in low if p[1] >= 1.3)
    print("| %s | %s | %s (%d/%d \\| %d/%d) |" % (path, head, " | ".join(cells), n_lo, t_lo,
                                                 n_hi, t_hi))
    if n_worst:
        worst = sorted((p for p in low if p[1] >= 1.3), key=lambda p: -p[4])[:n_worst]
        for p in worst:
            print("   %s m %.4f delta %.4f P/P(m) %.2e tot %.2e" % (p[0], p[1], p[2], p[3],
                                                                     p[4]))


def main():
    args = sys.argv[1:]
    n_worst = 0
    if "--worst" in args:
        k = args.index("--worst")
        n_worst = int(args[k + 1])
        del args[k:k + 2]
    for path in args:
        table(path, n_worst)


if __name__ == "__main__":
    main()
