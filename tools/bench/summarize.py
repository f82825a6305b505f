#!/usr/bin/env python3
"""Markdown tables of one egw-bench run (doc/bench/*.csv), for doc/benchmarks.md.

Usage: python3 tools/bench/summarize.py [DIR]   (default doc/bench). Standard library only.
"""
import csv
import sys
from collections import defaultdict

d = sys.argv[1] if len(sys.argv) > 1 else "doc/bench"


def rows(name):
    with open(f"{d}/{name}") as f:
        return list(csv.DictReader(f))


def ms(t):
    return f"{float(t) * 1e3:.2f} ms"


def it(extra):
    for tok in extra.split():
        if tok.startswith("iter="):
            return tok[5:]
    return "?"


solver = rows("solver.csv")
print("Newton against Picard, automatic mesh (time, iterations of the final level, error):\n")
print("| case | Newton 1e-6 | Picard 1e-6 | Newton 1e-9 | Picard 1e-9 |")
print("|---|---|---|---|---|")
cases = []
for r in solver:
    if r["case"] not in cases:
        cases.append(r["case"])
get = {(r["method"], r["case"], r["setting"]): r for r in solver}
for c in cases:
    cells = []
    for tol in ("1.0E-06", "1.0E-09"):
        for m in ("newton auto-mesh", "picard auto-mesh"):
            r = get.get((m, c, f"rel_tol={tol}"))
            if r is None or r["status"] != "0":
                cells.append("failed")
            else:
                cells.append(f"{ms(r['time_s'])} ({it(r['extra'])} it, {float(r['rel_err']):.1e})")
    print(f"| {c} | " + " | ".join([cells[0], cells[1], cells[2], cells[3]]) + " |")

print("\nFixed meshes (Newton, all cases): worst error and range of times per n_radial:\n")
by_n = defaultdict(list)
for r in solver:
    if r["method"] == "newton fixed-mesh" and r["status"] == "0":
        by_n[int(r["setting"].split("=")[1])].append(r)
ns = sorted(by_n)
print("| n_radial | " + " | ".join(str(n) for n in ns) + " |")
print("|---|" + "---|" * len(ns))
print("| worst error | " + " | ".join(f"{max(float(r['rel_err']) for r in by_n[n]):.1e}" for n in ns) + " |")
print("| time | " + " | ".join(
    f"{min(float(r['time_s']) for r in by_n[n]) * 1e3:.2f}–{max(float(r['time_s']) for r in by_n[n]) * 1e3:.2f} ms"
    for n in ns) + " |")

print("\nE-GW at the default rel_tol = 1e-6 (Newton, automatic mesh, one thread):\n")
print("| case | time | error vs reference | est_rel_err |")
print("|---|---|---|---|")
for r in rows("solver_target.csv"):
    print(f"| {r['case']} | {ms(r['time_s'])} | {float(r['rel_err']):.1e} | {float(r['est_rel_err']):.1e} |")

print("\nTable evaluation (force and stiffness together), DEM collision mix:\n")
print("| table | ns/call | / Hertz force | / Hertz force+stiffness | error | nodes |")
print("|---|---|---|---|---|---|")
for r in rows("tables.csv"):
    ex = dict(tok.split("=", 1) for tok in r["extra"].split() if "=" in tok)
    if "ratio_F" in ex and r["method"] != "E-GW table linear":
        print(f"| {r['method']} {r['setting']} | {float(r['time_s']) * 1e9:.2f} | "
              f"{float(ex['ratio_F']):.2f} | {float(ex.get('ratio_FK', 'nan')):.2f} | "
              f"{float(r['rel_err']):.1e} | {ex.get('nodes', '')} |")
