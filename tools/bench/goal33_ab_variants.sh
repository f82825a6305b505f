#!/bin/sh
# One A/B round (tools/bench/rough_cap_ab.sh, E-GW and EP-GW + cap) per weighting variant:
# A = main's egw-table, B = the measuring copy's (tools/bench/goal33_measuring.patch), the
# switches in the environment (main ignores them). doc/benchmarks.md "Stop 66: goal33".
# usage: sh tools/bench/goal33_ab_variants.sh MAIN_egw-table MEASURING_egw-table OUTDIR
a=$1; b=$2; out=$3
run() { name=$1; shift
  env "$@" ROUNDS=1 MODELS="E-GW EP-GW" sh tools/bench/rough_cap_ab.sh "$a" "$b" "$out/$name" \
    > "$out/$name.txt" 2>&1; }
run DL EGW_L31_GOAL=2 EGW_G33_SKIP=1 EGW_G33_LSHARE=0.25 EGW_G33_MC=4 EGW_G33_MCUT=1e-3
run T5 EGW_L31_GOAL=4 EGW_G33_SKIP=1 EGW_G33_LSHARE=0.25 EGW_G33_MC=8 EGW_G33_MCUT=1e-3
run A15c EGW_L31_GOAL=2 EGW_G33_SKIP=1 EGW_G33_LSHARE=0.25 EGW_G33_MC=1.5 EGW_G33_MCUT=1e-3
