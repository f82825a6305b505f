#!/usr/bin/env python3
"""Stop 65 (dbg31): force of each refinement level of an unloading solve after a capped
loading, summed by zone between radii every level has as element edges (the Hertz radius
a, a_max, the rim), from the stderr of a solve built with tools/bench/dbg31_probe.patch.

usage: python3 tools/bench/dbg31_zones.py LEVELS.txt [LEVELS2.txt ...]
One line a level: file, step, elements, force, estimate, then the force (scaled units) in
[0, a], [a, a_max], [a_max, rim], [rim, outer] (Gauss sums of the total pressure; the
solver's closed form inside a is not applied, so a zone can differ from the solver's sum
by the Gauss sum's error at p_s's sqrt edge, alike on every level).
"""
import math
import sys


def number(text):
    """A Fortran es field; exponents past 99 print without the E (underflow: 0)."""
    return float(text) if "E" in text else 0.0


def levels_of(path):
    """The levels of a probe log: step, force, estimate, zone radii, element forces."""
    levels = []
    for line in open(path):
        fields = line.split()
        if line.startswith("DBG lev"):
            levels.append({"step": float(fields[4]), "force": float(fields[10]),
                           "est": float(fields[fields.index("est") + 1]), "elements": {}})
        elif line.startswith("DBGP") and levels:
            levels[-1]["radii"] = [float(x) for x in fields[1:]]
        elif line.startswith("DBGG") and levels:
            element = int(fields[1])
            r0, _, r, w, p, p_s = (number(x) for x in fields[2:])
            start, force = levels[-1]["elements"].get(element, (r0, 0.0))
            levels[-1]["elements"][element] = (start, force + 2.0 * math.pi * w * r * (p + p_s))
    return [level for level in levels if level["elements"]]


def main():
    for path in sys.argv[1:]:
        for level in levels_of(path):
            a, rim, _, a_max, _ = level["radii"]
            cuts = sorted([a, a_max, rim])
            zones = [0.0] * (len(cuts) + 1)
            for start, force in level["elements"].values():
                zones[sum(1 for c in cuts if start >= c * (1.0 - 1e-14))] += force
            print("%-12s step %.4f elements %3d force %.6f est %.1e  %s" % (
                path, level["step"], len(level["elements"]), level["force"], level["est"],
                " ".join("%.5f" % z for z in zones)))


if __name__ == "__main__":
    main()
