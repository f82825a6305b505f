#!/bin/sh
# Replay of rough_cap_local_decompose against stored references with the measuring copy's
# switches (tools/bench/goal33_measuring.patch; doc/benchmarks.md "Stop 66: goal33").
# usage: DECOMPOSE=/path/to/rough_cap_local_decompose REFS=refs.txt \
#        sh tools/bench/goal33_replay.sh NAME [ENV=VALUE ...]
# writes r_NAME.txt in the current directory; `python3 tools/bench/goal33_bands.py r_NAME.txt`
# gives its band table. E.g. sh tools/bench/goal33_replay.sh A15L EGW_L31_GOAL=2 \
#   EGW_G33_SKIP=1 EGW_G33_LSHARE=0.25 EGW_G33_MC=1.5
name=$1; shift
env "$@" OMP_NUM_THREADS=1 "${DECOMPOSE:?}" 1e-4 12 1e-8 1 "${REFS:?}" > "r_$name.txt" 2>/dev/null
