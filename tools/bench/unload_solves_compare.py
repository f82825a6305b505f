#!/usr/bin/env python3
"""Compare the outputs of unload_solves_compare.f90 built against two libraries
(doc/benchmarks.md "Stop 44: rough + cap builds").

usage: unload_solves_compare.py MAIN.txt BRANCH.txt

Both must hold the same (delta_max, delta) rows. Prints max |dP|/P(m) (P(m) the loading
force at the turning point), max and median |dP|/|P|, and the largest |dP|/|P| over the
larger of the two solves' error estimates.
"""
import sys
import numpy as np


def main():
    a = np.loadtxt(sys.argv[1])
    b = np.loadtxt(sys.argv[2])
    if a.shape != b.shape or np.any(a[:, :2] != b[:, :2]):
        sys.exit("the two files do not hold the same (delta_max, delta) rows")
    d = np.abs(a[:, 2] - b[:, 2])
    rel_pm = d / a[:, 4]
    rel_p = d / np.maximum(np.abs(a[:, 2]), 1e-300)
    est = np.maximum(a[:, 3], b[:, 3])
    i = rel_pm.argmax()
    print(f"{len(a)} solves: max |dP|/P(m) {rel_pm.max():.2e} (m {a[i, 0]:.0f}, delta "
          f"{a[i, 1]:.1f}), max |dP|/|P| {rel_p.max():.2e}, median {np.median(rel_p):.1e}, "
          f"max (|dP|/|P|)/estimate {np.max(rel_p / est):.2e}")


if __name__ == "__main__":
    main()
