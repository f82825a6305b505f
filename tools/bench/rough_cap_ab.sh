#!/bin/sh
# Two egw-table binaries alternated on the README's rough + cap 1e-4 builds (issue 32;
# doc/benchmarks.md "Stop 52 (speed18)"): E-GW + cap, EP-GW + cap, GW + cap, Hertz + cap,
# THREADS threads (default 2), ROUNDS rounds (default 3); prints "round model A|B wall user sys" per build
# and the load after each round. MODELS picks the builds (default "E-GW EP-GW GW Hertz";
# "psi1" is EP-GW + cap with --psi 1).
# usage: tools/bench/rough_cap_ab.sh A_egw-table B_egw-table [OUTDIR]
a=$1; b=$2; out=${3:-/tmp/rough_cap_ab}
[ -x "$a" ] && [ -x "$b" ] || { echo "usage: $0 A_egw-table B_egw-table [OUTDIR]" >&2; exit 2; }
mkdir -p "$out"
for round in $(seq 1 "${ROUNDS:-3}"); do
  for m in ${MODELS:-E-GW EP-GW GW Hertz}; do
    model=$m; extra=
    if [ $m = psi1 ]; then model=EP-GW; extra="--psi 1"; fi
    for which in A B; do
      if [ $which = A ]; then bin=$a; else bin=$b; fi
      EGW_CACHE_DIR=off OMP_NUM_THREADS=${THREADS:-2} /usr/bin/time -f "$round $m $which %e %U %S" "$bin" \
        --radius 810569.469138702 --effective-modulus 1 --sigma 1 --mu 4 --delta-min 0 \
        --delta-max 600 --tol 1e-4 -q --flow-pressure 0.01 --model $model $extra \
        --out "$out/${which}_$m" 2>&1 >/dev/null | tail -n 1
    done
  done
  uptime
done
