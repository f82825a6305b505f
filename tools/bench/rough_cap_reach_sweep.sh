#!/bin/bash
# Which rough + cap hysteresis tables build at small sigma/delta_y (issue 32,
# doc/stability.md "Stop 51 (tiny17)"): egw-table's normalised scene (E* = 1, sigma = 1,
# mu 4, p_y = 0.01 E*; the pair's R = half the --radius, R = 2.0264e7/(RATIO/2e-4) so that
# delta_y = 1/RATIO sigma) from 0 to REACH delta_y at TOL, one thread, no cache, at most
# LIMIT s each. Prints the exit status, wall and CPU seconds and egw-table's error line.
#
# usage: rough_cap_reach_sweep.sh EGW_TABLE TOL LIMIT_S "RATIO REACH MODEL [--psi PSI]" ...
# e.g.   rough_cap_reach_sweep.sh build/gfortran_*/app/egw-table 1e-3 150 "2e-5 4 E-GW" \
#            "1e-5 2.5 E-GW" "1e-5 2 EP-GW --psi 1"
bin=$1 tol=$2 limit=$3
shift 3
out=$(mktemp -d)
for spec in "$@"; do
  set -- $spec
  ratio=$1 reach=$2 model=$3
  shift 3
  radius=$(python3 -c "print(40528473.45693511*2e-4/$ratio)")
  dmax=$(python3 -c "print($reach/$ratio)")
  start=$(date +%s.%N)
  EGW_CACHE_DIR=off OMP_NUM_THREADS=1 /usr/bin/time -f "cpu %U s" timeout "$limit" "$bin" -q \
    --radius "$radius" --effective-modulus 1 --sigma 1 --mu 4 --flow-pressure 0.01 \
    --delta-min 0 --delta-max "$dmax" --tol "$tol" --model "$model" "$@" --formats binary \
    -o "$out/t" > "$out/log" 2>&1
  rc=$?
  wall=$(python3 -c "import time; print(round(time.time() - $start, 1))")
  echo "sigma/delta_y $ratio, $reach delta_y ($dmax sigma), $model $*: rc $rc, wall $wall s," \
    "$(grep -o 'cpu .*' "$out/log") $(grep -o 'egw-table: .*' "$out/log" | cut -c1-240)"
done
rm -rf "$out"
