#!/usr/bin/env python3
"""An unloading solve's phases in a perf profile of egw-table (doc/benchmarks.md "Stop 63:
unl29"): each sample's stack is attributed to the first frame it passes of
first_unloading_level (by call site: the locating solve's and the first level's calls),
relocate_kinks, add_kink_error or refine_levels, else "other"; prints sample counts.

usage: EGW_CACHE_DIR=off OMP_NUM_THREADS=1 perf record -F 400 --call-graph dwarf,16384 \
           -o P.data egw-table ... ;  perf script -i P.data -F ip,sym,symoff > P.txt
       tools/bench/unl29_phase_split.py P.txt
(the call-site offsets depend on the build: read them against `objdump -d`.)
"""
import collections
import sys


def samples(path):
    cur = []
    for line in open(path):
        line = line.strip()
        if not line:
            if cur:
                yield cur
            cur = []
            continue
        parts = line.split(None, 1)
        cur.append(parts[-1])
    if cur:
        yield cur


def phase(stack):
    for frame in stack:
        if "first_unloading_level" in frame:
            return "first_unloading_level+" + frame.split("+")[-1]
        for name in ("relocate_kinks", "add_kink_error", "refine_levels"):
            if name in frame:
                return name
    return "other"


def main():
    counts = collections.Counter(phase(s) for s in samples(sys.argv[1]))
    total = sum(counts.values())
    print(f"{total} samples")
    for key, n in counts.most_common():
        print(f"{n:6d} {100 * n / total:5.1f} %  {key}")


if __name__ == "__main__":
    main()
