#!/bin/sh
# Three test suites (rough_cap_hysteresis, cap_hysteresis, hysteresis) of two testers, one
# suite at a time, B then A, each run from its own project directory (tests read and write
# under test/ and build/): pass/fail and /usr/bin/time's wall, user, sys per run, and the
# load after each (doc/benchmarks.md "Stop 67: probe33").
# usage: tools/bench/probe33_suites.sh A_TESTER A_DIR B_TESTER B_DIR [OUTDIR]
a=$1; ad=$2; b=$3; bd=$4; out=${5:-/tmp/probe33_suites}
[ -x "$a" ] && [ -x "$b" ] && [ -d "$ad" ] && [ -d "$bd" ] || {
  echo "usage: $0 A_TESTER A_DIR B_TESTER B_DIR [OUTDIR]" >&2; exit 2; }
mkdir -p "$out"
for s in rough_cap_hysteresis cap_hysteresis hysteresis; do
  for which in B A; do
    if [ $which = A ]; then t=$a; d=$ad; else t=$b; d=$bd; fi
    (cd "$d" && /usr/bin/time -f "$which $s %e s wall %U user %S sys" "$t" $s \
      > "$out/suite_${which}_$s.log" 2>&1)
    tail -n 1 "$out/suite_${which}_$s.log"
    grep -E '^[0-9]+ passed' "$out/suite_${which}_$s.log"
    uptime
  done
done
