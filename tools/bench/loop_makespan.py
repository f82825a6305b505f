#!/usr/bin/env python3
"""The 2-thread makespan of a hysteresis build's OpenMP loops, from per-iteration thread
CPU times (doc/benchmarks.md "Stop 56: par22"): robust where walls are not (a shared,
loaded machine), since each iteration's cost is its own thread's CPU time.

Measure (a worktree, never committed; fpm test/build as README):
    git apply tools/bench/loop_probe.patch && fpm build --profile release
    EGW_CACHE_DIR=off OMP_NUM_THREADS=1 egw-table ... 2> probe.txt
    git apply -R tools/bench/loop_probe.patch

usage: loop_makespan.py probe.txt [more.txt ...] [--threads N] [--loops]

Per file: the loops' summed iteration CPU ("sum"); their makespan on N threads (default
2) simulated as the dynamic schedule (chunk 1) hands iterations out, in increasing index
("increasing"), in decreasing index ("decreasing"), longest first ("sorted"), and the
bound max(sum/N, largest iteration) ("ideal"), each loop after the one before (their
barriers kept); "busiest": the busier thread's summed iteration CPU as the run itself
scheduled them (a run on N threads); and the phases' process CPU (PHASE lines).
"""
import argparse
import heapq
from collections import OrderedDict, defaultdict


def list_schedule(costs, threads):
    """Makespan of handing costs out in order to the first free of `threads` threads."""
    free = [0.0] * threads
    for c in costs:
        heapq.heappush(free, heapq.heappop(free) + c)
    return max(free)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--loops", action="store_true", help="one line per loop too")
    args = ap.parse_args()
    n = args.threads
    for path in args.files:
        loops = OrderedDict()
        phases = defaultdict(float)
        for line in open(path):
            f = line.split()
            if f and f[0] == "ITEM":   # ITEM name loop index cpu thread
                loops.setdefault((int(f[2]), f[1]), []).append((int(f[3]), float(f[4]),
                                                                 int(f[5])))
            elif f and f[0] == "PHASE":   # PHASE name wall cpu
                phases[f[1]] += float(f[3])
        tot = defaultdict(float)
        for (no, name), items in loops.items():
            items.sort()
            costs = [c for _, c, _ in items]
            per_thread = defaultdict(float)
            for _, c, t in items:
                per_thread[t] += c
            row = {"sum": sum(costs), "increasing": list_schedule(costs, n),
                   "decreasing": list_schedule(costs[::-1], n),
                   "sorted": list_schedule(sorted(costs, reverse=True), n),
                   "ideal": max(sum(costs) / n, max(costs)),
                   "busiest": max(per_thread.values())}
            for k, v in row.items():
                tot[k] += v
            if args.loops:
                print(f"  loop {no:3d} {name:7s} n={len(costs):3d} " +
                      " ".join(f"{k} {v:.4f}" for k, v in row.items()))
        print(path + ": " + ", ".join(f"{k} {v:.3f}" for k, v in tot.items()))
        keep = ["loading_table", "cap_reached", "first_yield", "lengths", "first_curves",
                "refine_m", "resample", "prepare", "TOTAL"]
        print("  phases (process CPU): " + ", ".join(f"{k} {phases[k]:.4f}" for k in keep
                                                     if k in phases))


if __name__ == "__main__":
    main()
