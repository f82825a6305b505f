#!/usr/bin/env python3
"""The s-midpoint estimates of rough + cap builds against the solves they replace
(doc/benchmarks.md, "Stop 60: grid26").

Reads the AUDIT lines that an egw-table built with tools/bench/grid26_midpoint_audit.patch
prints on stderr under EGW_MIDPOINT_AUDIT=1 (every midpoint solved: "AUDIT m n err q a b",
the neighbours' estimate n, the solve's mismatch err and the quintic's q in units of the
bisection's bound rel_tol/4, the interval [a, b]) and prints, per rule and threshold, the
midpoints it clears, how many of those the solve would split (err > 1) and the largest err.

usage: EGW_MIDPOINT_AUDIT=1 egw-table ... 2>&1 >/dev/null | grep AUDIT | grid26_midpoint_audit.py
"""
import sys

FIRST = {0.0, 0.5, 0.75, 1.0}   # the mapped curves' first nodes (s = 0, s_knee, s_zero, 1)


def main():
    rows = []
    for line in sys.stdin:
        f = line.split()
        if f and f[0] == "AUDIT":
            rows.append(tuple(float(x) for x in f[1:7]))
    print(f"{len(rows)} midpoints solved, {sum(r[1] < 1e29 for r in rows)} with both neighbours' interval")
    rules = []
    for th in (0.3, 0.6):
        rules.append((f"n <= {th}", lambda r, th=th: r[1] <= th))
    for th in (0.1, 0.3):
        rules.append((f"q <= {th}", lambda r, th=th: r[3] <= th))
    rules.append(("q <= 0.1 off first nodes", lambda r: r[3] <= 0.1 and not (r[4] in FIRST or r[5] in FIRST)))
    rules.append(("max(q, n) <= 0.3", lambda r: max(r[1], r[3]) <= 0.3))
    for tb in (0.2, 0.3):
        rules.append((f"q <= 0.1 off first nodes or max(q, n) <= {tb}",
                      lambda r, tb=tb: (r[3] <= 0.1 and not (r[4] in FIRST or r[5] in FIRST))
                      or max(r[1], r[3]) <= tb))
    for name, rule in rules:
        sel = [r for r in rows if rule(r)]
        worst = max((r[2] for r in sel), default=0.0)
        print(f"  {name:45s} cleared {len(sel):5d}, split by the solve {sum(r[2] > 1 for r in sel):3d}, "
              f"largest solve mismatch {worst:.3f}")


if __name__ == "__main__":
    main()
