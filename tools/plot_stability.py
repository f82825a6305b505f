#!/usr/bin/env python3
"""Draw the solver's stability map from the CSV written by the example stability-map.

    fpm run --profile release --example stability-map -- out/stability_map.csv
    python3 tools/plot_stability.py --data out/stability_map.csv --out doc/stability
or, to do both (and refresh the committed copy doc/stability/stability_map.csv):
    python3 tools/plot_stability.py --run

Writes one map per method (stability_auto.png, stability_newton.png,
stability_picard.png): panels over (delta/sigma, mu) for classic GW, E-GW and a few EP-GW
(psi, K); a filled marker is a converged solve coloured by its iteration count, a red cross
a NOT_CONVERGED one. stability_error.png shows the force error of every converged solve
against its reference, with rel_tol. Installs matplotlib with pip when it is missing.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

METHODS = ["AUTO", "NEWTON", "PICARD"]
PANELS = [("GW", 0.0, 0.6, "classic GW"), ("EGW", 0.0, 0.6, "E-GW"),
          ("EPGW", 1.0, 0.6, "EP-GW psi=1, K=0.6"), ("EPGW", 10.0, 0.2, "EP-GW psi=10, K=0.2"),
          ("EPGW", 50.0, 0.95, "EP-GW psi=50, K=0.95")]
REL_TOL = 1e-6


def import_pyplot():
    try:
        import matplotlib
    except ImportError:
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "matplotlib"])
        import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def read_rows(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = []
    for r in csv.DictReader(lines):
        rows.append({"model": r["model"].strip(), "method": r["method"].strip(),
                     "mu": float(r["mu"]), "delta": float(r["delta_over_sigma"]),
                     "psi": float(r["psi"]), "K": float(r["K"]), "status": int(r["status"]),
                     "iterations": int(r["iterations"]), "error": float(r["error"])})
    return rows


def delta_axis(d):
    """Signed log axis for delta/sigma in [-10, 1e5]: asinh keeps 0 and negatives."""
    return math.asinh(d)


def draw_maps(plt, rows, out):
    ticks = [-10, -1, 0, 1, 10, 100, 1e3, 1e4, 1e5]
    for method in METHODS:
        fig, axes = plt.subplots(1, len(PANELS), figsize=(4.0 * len(PANELS), 3.6), sharey=True)
        sc = None
        for ax, (model, psi, hard, title) in zip(axes, PANELS):
            sel = [r for r in rows if r["method"] == method and r["model"] == model
                   and (model != "EPGW" or (r["psi"] == psi and r["K"] == hard))]
            ok = [r for r in sel if r["status"] == 0]
            bad = [r for r in sel if r["status"] != 0]
            sc = ax.scatter([delta_axis(r["delta"]) for r in ok], [r["mu"] for r in ok],
                            c=[max(r["iterations"], 0.5) for r in ok], cmap="viridis",
                            norm=plt.matplotlib.colors.LogNorm(vmin=0.5, vmax=3000), s=60,
                            marker="o", edgecolors="k", linewidths=0.4)
            if bad:
                ax.scatter([delta_axis(r["delta"]) for r in bad], [r["mu"] for r in bad],
                           c="red", s=70, marker="x", linewidths=2, label="not converged")
                ax.legend(loc="lower left", fontsize=7)
            ax.set_yscale("log")
            ax.set_xticks([delta_axis(t) for t in ticks])
            ax.set_xticklabels(["-10", "-1", "0", "1", "10", "1e2", "1e3", "1e4", "1e5"],
                               fontsize=7)
            ax.set_xlabel("delta/sigma")
            ax.set_title(title, fontsize=9)
            ax.grid(alpha=0.3)
        axes[0].set_ylabel("mu")
        fig.colorbar(sc, ax=axes, label="iterations (final level)", shrink=0.9)
        fig.suptitle(f"egw stability map: method {method} (default options, rel_tol = 1e-6)",
                     fontsize=11)
        name = os.path.join(out, f"stability_{method.lower()}.png")
        fig.savefig(name, dpi=110, bbox_inches="tight")
        plt.close(fig)
        print("wrote", name)


def draw_errors(plt, rows, out):
    fig, ax = plt.subplots(figsize=(7, 4))
    markers = {"AUTO": "o", "NEWTON": "s", "PICARD": "^"}
    for method in METHODS:
        ok = [r for r in rows if r["method"] == method and r["status"] == 0 and r["error"] > 0]
        ax.scatter([delta_axis(r["delta"]) for r in ok], [r["error"] for r in ok], s=10,
                   marker=markers[method], label=method, alpha=0.5)
    ax.axhline(REL_TOL, color="red", lw=1, label="rel_tol = 1e-6")
    ax.set_yscale("log")
    ticks = [-10, -1, 0, 1, 10, 100, 1e3, 1e4, 1e5]
    ax.set_xticks([delta_axis(t) for t in ticks])
    ax.set_xticklabels(["-10", "-1", "0", "1", "10", "1e2", "1e3", "1e4", "1e5"])
    ax.set_xlabel("delta/sigma")
    ax.set_ylabel("|P - P_ref| / P_ref")
    ax.set_title("force error of every converged solve of the map")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    name = os.path.join(out, "stability_error.png")
    fig.savefig(name, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print("wrote", name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", default="out/stability_map.csv")
    parser.add_argument("--out", default="doc/stability")
    parser.add_argument("--run", action="store_true",
                        help="run the example first and copy its CSV to --out")
    args = parser.parse_args()
    if args.run:
        subprocess.check_call(["fpm", "run", "--profile", "release", "--example",
                               "stability-map", "--", args.data])
    os.makedirs(args.out, exist_ok=True)
    if args.run:
        shutil.copy(args.data, os.path.join(args.out, "stability_map.csv"))
    plt = import_pyplot()
    rows = read_rows(args.data)
    draw_maps(plt, rows, args.out)
    draw_errors(plt, rows, args.out)


if __name__ == "__main__":
    main()
