#!/bin/sh
# CPU time per evaluation of tools/bench/separated_hysteresis.c's cases for binaries built
# from different commits, interleaved, for a loaded machine (doc/benchmarks.md "Stop 52
# (tail18)"): `perf stat -e task-clock` counts only the time the process ran, so a
# preemption by other jobs does not enter (a shared core's slower pace still does). Per
# case: (3 rounds - 1 round)/2/2^22 ns, REPS times (default 5), each binary in turn; then
# the minimum per binary and case, less the same binary's minimum of "none" (the inline
# Hertz loop alone), and its ratio to that Hertz minimum.
# Usage: sh tools/bench/separated_hysteresis_cpu.sh BINARY...   (CASES="...", REPS=N)
export OMP_NUM_THREADS=1
log=$(mktemp)
tc() { perf stat -e task-clock -x, "$@" 2>&1 >/dev/null | grep task-clock | cut -d, -f1; }
for i in $(seq "${REPS:-5}"); do
  for c in none ${CASES:-tail-fresh-call tail-history-call tail-fresh-inline \
      tail-history-inline}; do
    for b in "$@"; do
      a=$(tc "$b" 1 "$c")
      z=$(tc "$b" 3 "$c")
      echo "$b $c $(python3 -c "print(($z - $a) / 2 / 2**22 * 1e6)")" >>"$log"
    done
  done
done
python3 - "$log" <<'PY'
import sys
from collections import defaultdict
t = defaultdict(list)
for line in open(sys.argv[1]):
    b, c, x = line.split()
    t[(b, c)].append(float(x))
for (b, c), v in sorted(t.items()):
    if c == "none":
        continue
    h = min(t[(b, "none")])
    print(f"{b} {c:22s} {min(v) - h:6.2f} ns  {(min(v) - h) / h:5.2f}x Hertz ({h:.2f} ns)"
          f"  runs {' '.join(f'{x:.2f}' for x in sorted(v))}")
PY
rm -f "$log"
