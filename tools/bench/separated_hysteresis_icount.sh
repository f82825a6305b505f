#!/bin/sh
# Instructions per evaluation of tools/bench/separated_hysteresis.c's cases (doc/benchmarks.md
# "Stop 51 (tailc17)"), load-independent: valgrind's I refs (cachegrind, no cache
# simulation) of a binary at 3 rounds less at 1 round, halved, over 2^22 evaluations, less
# the inline Hertz loop's (the case "none" runs Hertz alone). Where `perf stat -e
# instructions` works, it gives the same differences.
# Usage: sh tools/bench/separated_hysteresis_icount.sh BINARY...   (CASES="..." to choose)
export OMP_NUM_THREADS=1
refs() {
  valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null "$@" 2>&1 \
    >/dev/null | grep "I *refs" | sed 's/.*refs: *//; s/,//g'
}
per_eval() { python3 -c "print(($2 - $1) / 2 / 2**22 - $3)"; }
for b in "$@"; do
  hertz=$(per_eval "$(refs "$b" 1 none)" "$(refs "$b" 3 none)" 0)
  printf '%s Hertz loop %.2f\n' "$b" "$hertz"
  for c in ${CASES:-beyond-fresh-inline beyond-fresh-call beyond-history-inline \
      beyond-history-call tail-fresh-inline tail-fresh-call tail-history-inline \
      tail-history-call}; do
    printf '%s %-22s %.2f instructions/evaluation\n' "$b" "$c" \
      "$(per_eval "$(refs "$b" 1 "$c")" "$(refs "$b" 3 "$c")" "$hertz")"
  done
done
