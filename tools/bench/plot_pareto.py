#!/usr/bin/env python3
"""Speed-accuracy chart of every egw method (issue 5 item 1) -> doc/bench/speed_accuracy.png.

Reads the CSVs written by one run of egw-bench (doc/bench/fn.csv, solver.csv, tables.csv,
universal.csv, unloading.csv, hysteresis.csv; common columns section,method,case,setting,time_s,rel_err,...) and, if
present, doc/bench/peer.csv from tools/bench/peer_greenwood_tripp.py. Draws log10(error)
against log10(time per evaluation) with one panel per kind of evaluation (they differ by
up to 9 orders of magnitude in time and answer different questions):
  (a) F_3/2 kernel paths, (b) one full force solve (mesh, tolerance, Newton/Picard, peer),
  (c) force evaluation from tables (1-D Hermite/linear at each resolution, universal).
The Pareto front (no other point both faster and more accurate) is marked in each panel.
Panel (b) has one point per solver configuration (method and rel_tol or n_radial): the
mean time over the benchmark's cases and the worst error among them; the peer's points
are its runs on the classic-GW cases of doc/bench/peer.csv, grouped the same way.
Errors of exactly 0 or below 1e-16 are drawn at 1e-16 (double precision floor).
Run from the project root:  python3 tools/bench/plot_pareto.py
"""
import csv
import math
import os
import subprocess
import sys

try:
    import matplotlib
except ImportError:  # the script installs what it needs
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "matplotlib"])
    import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402,F401

DIR = "doc/bench"
FLOOR = 1e-16


def read(name):
    path = os.path.join(DIR, name)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def points(rows):
    """(method, time, error, label) for rows with a valid error."""
    out = []
    for r in rows:
        t = float(r["time_s"])
        e = float(r["rel_err"])
        if e < 0 or int(r["status"]) != 0 or t <= 0:
            continue
        out.append((r["method"], t, max(e, FLOOR), r["case"] + " " + r["setting"]))
    return out


def by_configuration(pts):
    """One point per configuration (method + setting) over the cases it was run on: the
    mean time and the WORST error (a configuration is only as good as its worst case)."""
    groups = {}
    for m, t, e, label in pts:
        setting = label.split(" ")[-1]
        groups.setdefault((m, setting), []).append((t, e))
    out = []
    for (m, setting), v in groups.items():
        out.append((m, sum(t for t, _ in v) / len(v), max(e for _, e in v),
                    f"{setting} ({len(v)} cases)"))
    return out


def pareto(pts):
    """Indices of the points that no other point beats in both time and error."""
    order = sorted(range(len(pts)), key=lambda i: (pts[i][1], pts[i][2]))
    front, best = [], math.inf
    for i in order:
        if pts[i][2] < best * (1 - 1e-2):  # 1 % better, not a rounding tie
            front.append(i)
            best = pts[i][2]
    return front


def panel(ax, pts, title, ylabel="relative error of the force"):
    methods = sorted({p[0] for p in pts})
    markers = "osD^v<>ph*X"
    for k, m in enumerate(methods):
        sel = [p for p in pts if p[0] == m]
        ax.scatter([p[1] for p in sel], [p[2] for p in sel], s=18, alpha=0.75,
                   marker=markers[k % len(markers)], label=m)
    if len(pts) <= 24:  # few points: name their setting
        for p in pts:
            setting = p[3].split(" ")[-1] if "(" not in p[3] else p[3].split(" (")[0]
            if setting not in ("-", ""):
                ax.annotate(setting.replace("rel_tol=", "").replace("tol=", ""),
                            (p[1], p[2]), fontsize=6, xytext=(3, 2),
                            textcoords="offset points", color="0.3")
    if pts:
        f = pareto(pts)
        ax.plot([pts[i][1] for i in f], [pts[i][2] for i in f], "k-", lw=1.2,
                label="Pareto front", zorder=5)
        ax.scatter([pts[i][1] for i in f], [pts[i][2] for i in f], s=60, facecolors="none",
                   edgecolors="k", zorder=6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation [s]")
    ax.set_ylabel(ylabel)
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="best")


def main():
    fn = points(read("fn.csv"))
    solver = points(read("solver.csv"))
    peer = read("peer.csv")
    for r in peer:
        solver.append(("peer: ContactMechanics GT n=" + r["peer_n"], float(r["peer_time_s"]),
                       max(float(r["peer_rel_err"]), FLOOR), "classic-GW"))
        solver.append(("egw GW rel_tol=1e-6 (peer cases)", float(r["egw_time_s"]),
                       max(float(r["egw_rel_err"]), FLOOR), "classic-GW"))
    # EP-GW unloading solves (egw-bench --unloading) against their independent references
    solver += [("EP-GW unloading (solve_unload)",) + pt[1:]
               for pt in points(read("unloading.csv")) if pt[0] == "solve_unload"]
    solver = by_configuration(solver)
    table_rows = read("tables.csv")
    hertz = {r["case"]: float(r["time_s"]) for r in table_rows
             if r["method"] == "hertz closed form"}
    tables = points([r for r in table_rows if r["section"] == "table"]) + \
        points(read("universal.csv")) + \
        [("EP-GW hysteresis table (unloading mix)",) + pt[1:]
         for pt in points(read("hysteresis.csv"))]
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.5))
    panel(axes[0], fn, "(a) F_3/2(h) evaluation paths", "max relative error of F_3/2")
    panel(axes[1], solver, "(b) one force point, full solve: mean time, worst error\n"
          "over the GW, E-GW, EP-GW cases (n_threads = 1)")
    panel(axes[2], tables, "(c) force from tables (E-GW, DEM collision mix;\n"
          "EP-GW hysteresis: loading/unloading mix)")
    for case, t in hertz.items():
        axes[2].axvline(t, color="grey", ls="--" if case == "F only" else ":", lw=1)
        axes[2].text(t, axes[2].get_ylim()[1], " Hertz " + case, rotation=90, va="top",
                     fontsize=7, color="grey")
    fig.suptitle("egw speed against accuracy (one run of egw-bench; error vs "
                 "independent references)", fontsize=11)
    fig.tight_layout()
    out = os.path.join(DIR, "speed_accuracy.png")
    fig.savefig(out, dpi=110)
    print("wrote", out)
    # the Pareto fronts as text, for doc/benchmarks.md
    for name, pts in (("F_n", fn), ("solve", solver), ("tables", tables)):
        print(f"Pareto front {name}:")
        for i in pareto(pts):
            print(f"  {pts[i][1]:.3e} s  err {pts[i][2]:.2e}  {pts[i][0]}: {pts[i][3]}")


if __name__ == "__main__":
    main()
