#!/bin/sh
# The unloading stiffness of two unload_point binaries (A, B) at rel_tol TOL against the
# central quotient of B's rel_tol QTOL forces at delta +- h, 2h, extrapolated
# (4 D(h) - D(2h))/3 (doc/benchmarks.md "Stop 63: stiffb29"; forces are the same on both
# where only the derivative differs).
# usage: tools/bench/unload_quotient.sh A B M "DELTAS" [TOL 1e-6] [QTOL 1e-9] [H 0.02]
a=$1; b=$2; m=$3; deltas=$4; tol=${5:-1e-6}; qtol=${6:-1e-9}; h=${7:-0.02}
for d in $deltas; do
  sa=$(OMP_NUM_THREADS=1 "$a" $m $d $tol | awk '{print $6}')
  sb=$(OMP_NUM_THREADS=1 "$b" $m $d $tol | awk '{print $6}')
  f=""
  for s in -2 -1 1 2; do
    dd=$(python3 -c "print($d + $s*$h)")
    f="$f $(OMP_NUM_THREADS=1 "$b" $m $dd $qtol | awk '{print $5}')"
  done
  python3 -c "
f = [float(x) for x in '$f'.split()]; h = $h
d1 = (f[2] - f[1])/(2*h); d2 = (f[3] - f[0])/(4*h); q = (4*d1 - d2)/3
print('m $m delta $d Q %.10e A %+.2e B %+.2e trunc %.1e' % (q, ($sa - q)/q, ($sb - q)/q, (d1 - d2)/q))"
done
