#!/usr/bin/env python3
"""CPU time of tools/bench/separated_hysteresis.c's cases for binaries built from different
sources, alternated case by case (stop 58: a loaded host without `perf stat`).
Usage: python3 tools/bench/separated_hysteresis_ab.py RUNS "CASE..." BINARY...
Each run calls every binary on every case (`OMP_NUM_THREADS=1 BINARY 5 CASE`: 5 rounds, its
minimum); prints per case and binary the minimum over the runs, its ratio to that binary's
smallest inline Hertz time, the median over the runs and its ratio to the binary's median
Hertz time (stop 59), and every run's time (their spread shows the load)."""
import collections
import os
import re
import statistics
import subprocess
import sys

runs, cases, bins = int(sys.argv[1]), sys.argv[2].split(), sys.argv[3:]
env = dict(os.environ, OMP_NUM_THREADS="1")
ns, hertz, loads = collections.defaultdict(list), collections.defaultdict(list), []
for _ in range(runs):
    loads.append(open("/proc/loadavg").read().split()[0])
    for case in cases:
        for b in bins:
            out = subprocess.run([b, "5", case], capture_output=True, text=True, env=env,
                                 check=True).stdout
            hertz[b].append(float(re.search(r"inline Hertz ([\d.]+) ns", out).group(1)))
            row = re.search(r"^\S+\s+\S+\s+\S+\s+([\d.]+) ns", out.split("\n", 2)[2], re.M)
            ns[(b, case)].append(float(row.group(1)))
print("load at each run:", " ".join(loads))
for case in cases:
    for b in bins:
        t = ns[(b, case)]
        med = statistics.median(t)
        print(f"{case:22s} {b:28s} min {min(t):6.2f} ns {min(t) / min(hertz[b]):5.2f}x  median "
              f"{med:6.2f} ns {med / statistics.median(hertz[b]):5.2f}x  runs "
              + " ".join(f"{x:.2f}" for x in t))
for b in bins:
    print(f"inline Hertz {b}: min {min(hertz[b]):.3f} ns, median "
          f"{statistics.median(hertz[b]):.3f} ns")
