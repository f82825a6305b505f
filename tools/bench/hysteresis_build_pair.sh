#!/bin/bash
# Build cost of two (or more) libraries' hysteresis tables, alternated in one run
# (doc/benchmarks.md "Stop 47 (local13)", "Stop 48 (local14)"): DIR holds nodes_A, nodes_B
# (...), tools/bench/hysteresis_nodes.f90 linked against each library (see its header);
# egw-bench's table (EP-GW mu 4, psi 2, [-3, 30] sigma) at 1e-4 and 1e-5, ROUNDS rounds
# (2), THREADS OpenMP threads (1: the user CPU is the cost, little moved by the load),
# cache off. Prints one line per build: round,
# rel_tol, library, load, grid, wall and user seconds.
#   tools/bench/hysteresis_build_pair.sh DIR A B [C ...]
dir=$1; shift
cd "$dir" || exit 1
for r in $(seq 1 "${ROUNDS:-2}"); do
  for tol in 1e-4 1e-5; do
    for lib in "$@"; do
      out=$(EGW_CACHE_DIR=off OMP_NUM_THREADS=${THREADS:-1} /usr/bin/time \
        -f "%e s wall, %U s user" "./nodes_$lib" 2.0 -3 30 "$tol" 2>&1 | grep -E "grid|user" | \
        tr '\n' ' ')
      echo "r$r $tol $lib load $(cut -d' ' -f1 /proc/loadavg): $out"
    done
  done
done
