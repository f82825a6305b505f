#!/usr/bin/env python3
"""Draw the paper's Figs. 3, 4, 5, 7 and 8 (Zhao & Feng 2018, corrected equations) from the
CSV files written by the example program paper-figures.

    fpm run --profile release --example paper-figures -- out/figures
    python3 tools/plot_figures.py --data out/figures --out doc/figures
or, to do both:
    python3 tools/plot_figures.py --run

Installs matplotlib with pip when it is missing. Writes fig3.png ... fig8.png.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
from collections import defaultdict


def import_pyplot():
    try:
        import matplotlib
    except ImportError:
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "matplotlib"])
        import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def read_csv(path):
    """Rows of a CSV whose leading '#' lines are comments; numbers become floats."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = []
    for row in csv.DictReader(lines):
        rows.append({k: _value(v) for k, v in row.items()})
    return rows


def _value(text):
    try:
        return float(text)
    except ValueError:
        return text


def series(rows, x, y, **match):
    """(xs, ys) of the rows whose fields equal match, sorted by x."""
    pts = sorted((r[x], r[y]) for r in rows if all(r[k] == v for k, v in match.items()))
    return [p[0] for p in pts], [p[1] for p in pts]


MU_COLOURS = {1.0: "tab:blue", 4.0: "tab:orange", 10.0: "tab:green"}
SIGMA_COLOURS = {1e-5: "tab:blue", 1e-4: "tab:orange", 1e-3: "tab:green"}
MODEL_STYLES = {"GW": "--", "E-GW": "-"}
DELTA = 0.01   # the paper's overlap, R = E = 1


def figure3(plt, rows, out, misprint_rows=None):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, log in zip(axes, (False, True)):
        for model in ("GW", "E-GW"):
            for mu, colour in MU_COLOURS.items():
                xs, ys = series(rows, "sigma", "force_ratio", model=model, mu=mu)
                ax.plot(xs, ys, MODEL_STYLES[model], color=colour, marker="." if log else None,
                        label=f"{model}, $\\mu$ = {mu:g}")
            if misprint_rows and not log:
                # doc/theory.md §6 misprint 1: the printed 3/4 of eq. 5 instead of 4/3
                xs, ys = series(misprint_rows, "sigma", "force_ratio", model=model, mu=4.0)
                ax.plot(xs, ys, MODEL_STYLES[model], color="grey", lw=0.8,
                        label=f"{model}, $\\mu$ = 4, eq. 5 as printed (3/4)")
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xlabel(r"$\sigma$ (R = E = 1, $\delta$ = 0.01)")
        ax.set_ylabel(r"$P^* = P/P_H$")
        if log:
            ax.set_xscale("log")
            ax.set_title(r"(b) the same, log $\sigma$: GW tends to Hertz from below")
        else:
            ax.set_xlim(0, 0.01)
            ax.set_title("(a) Fig. 3: GW against E-GW")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig3.png"), dpi=130)
    plt.close(fig)


def profiles(plt, rows, out, name, quantity, label, fig_no, mark_eq20=False):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    xs, ys = series(rows, "r", quantity, model="Hertz")
    axes[0].plot(xs, ys, "k-", lw=1.5, label="Hertz")
    axes[1].axhline(0.0, color="k", lw=1.0)
    for model in ("GW", "E-GW"):
        for sigma, colour in SIGMA_COLOURS.items():
            xs, ys = series(rows, "r", quantity, model=model, sigma=sigma)
            if not xs:
                continue
            lab = f"{model}, $\\sigma$ = {sigma:g}"
            axes[0].plot(xs, ys, MODEL_STYLES[model], color=colour, label=lab)
            xs, ys = series(rows, "r", quantity + "_difference", model=model, sigma=sigma)
            axes[1].plot(xs, ys, MODEL_STYLES[model], color=colour, label=lab)
            if mark_eq20 and model == "GW":
                # eq. (20), corrected (doc/theory.md §6 misprint 3): the sigma -> 0 asymptote of
                # w_H(0) - w_G(0); the printed bracket is 4/3 too large.
                mu = 4.0
                corrected = (4 * math.sqrt(2) * sigma / (math.pi * mu * DELTA))**(2 / 3) * DELTA
                printed = (16 * math.sqrt(2) * sigma / (3 * math.pi * mu * DELTA))**(2 / 3) * DELTA
                axes[1].plot([0], [-corrected], "o", color=colour, ms=6)
                axes[1].plot([0], [-printed], "o", mfc="none", color=colour, ms=8)
    for ax in axes:
        ax.set_xlabel("r (R = E = 1)")
        ax.axvline(math.sqrt(DELTA), color="grey", lw=0.6, ls=":")
    axes[0].set_ylabel(label)
    axes[1].set_ylabel(label + " minus Hertz")
    axes[0].set_title(f"(a) Fig. {fig_no}: $\\delta$ = 0.01, $\\mu$ = 4")
    title = f"(b) difference from Hertz"
    if mark_eq20:
        title += "\n(dots at r = 0: eq. 20 corrected, filled; as printed, open)"
    axes[1].set_title(title, fontsize=10)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=130)
    plt.close(fig)


EP_PANELS = {
    "a": ("psi", [2.0, 4.0, 10.0], r"(a) $K$ = 0.6, $\psi$ = 2, 4, 10", r"$\psi$"),
    "b": ("hardness_coeff", [0.4, 0.6, 0.8], r"(b) $\psi$ = 4, $K$ = 0.4, 0.6, 0.8", "K"),
}
EP_COLOURS = ["tab:orange", "tab:green", "tab:red"]


def figure7(plt, rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, (panel, (key, values, title, sym)) in zip(axes, EP_PANELS.items()):
        xs, ys = series(rows, "r", "pressure", model="Hertz")
        ax.plot(xs, ys, "k-", lw=1.2, label="Hertz")
        xs, ys = series(rows, "r", "pressure", model="E-GW")
        ax.plot(xs, ys, "-", color="tab:blue", lw=1.5, label="E-GW")
        for value, colour in zip(values, EP_COLOURS):
            xs, ys = series(rows, "r", "pressure", model="EP-GW", panel=panel, **{key: value})
            ax.plot(xs, ys, "--", color=colour, label=f"EP-GW, {sym} = {value:g}")
        ax.set_xlabel("r (R = E = 1)")
        ax.set_ylabel("pressure p(r)")
        ax.set_title("Fig. 7 " + title + "\n$\\delta$ = 0.01, $\\sigma$ = 0.001, $\\mu$ = 4",
                     fontsize=10)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig7.png"), dpi=130)
    plt.close(fig)


def figure8(plt, rows, out):
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), sharex=True,
                             gridspec_kw={"height_ratios": [2, 1]})
    egw_x, egw_y = series(rows, "delta", "force", model="E-GW")
    egw = dict(zip(egw_x, egw_y))
    for col, (panel, (key, values, title, sym)) in enumerate(EP_PANELS.items()):
        top, bottom = axes[0, col], axes[1, col]
        xs, ys = series(rows, "delta", "force", model="Hertz")
        top.plot(xs, ys, "k-", lw=1.2, label="Hertz")
        top.plot(egw_x, egw_y, "-", color="tab:blue", lw=1.5, label="E-GW")
        for value, colour in zip(values, EP_COLOURS):
            xs, ys = series(rows, "delta", "force", model="EP-GW", panel=panel, **{key: value})
            top.plot(xs, ys, "--", color=colour, label=f"EP-GW, {sym} = {value:g}")
            ratio = [(x, y / egw[x]) for x, y in zip(xs, ys) if egw.get(x, 0) > 0]
            bottom.plot([p[0] for p in ratio], [p[1] for p in ratio], "--", color=colour)
        top.set_ylabel("force P")
        top.set_title("Fig. 8 " + title + ", $\\sigma$ = 0.001, $\\mu$ = 4", fontsize=10)
        top.legend(fontsize=8)
        bottom.axhline(1.0, color="tab:blue", lw=1.0)
        bottom.set_ylabel(r"$P_{EP-GW}/P_{E-GW}$")
        bottom.set_xlabel(r"overlap $\delta$ (R = E = 1)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig8.png"), dpi=130)
    plt.close(fig)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.path.join(root, "out", "figures"),
                        help="folder with the CSV files (default out/figures)")
    parser.add_argument("--out", default=os.path.join(root, "doc", "figures"),
                        help="folder for the PNG files (default doc/figures)")
    parser.add_argument("--run", action="store_true",
                        help="first run the example program to (re)write the CSV files")
    args = parser.parse_args()
    if args.run:
        subprocess.check_call(["fpm", "run", "--profile", "release", "--example",
                               "paper-figures", "--", args.data], cwd=root)
    needed = ["fig3_force_ratio.csv", "fig4_pressure.csv", "fig5_deflection.csv",
              "fig7_pressure.csv", "fig8_force.csv"]
    missing = [n for n in needed if not os.path.exists(os.path.join(args.data, n))]
    if missing:
        sys.exit(f"missing {', '.join(missing)} in {args.data}: run "
                 f"'fpm run --profile release --example paper-figures -- {args.data}' "
                 "or pass --run")
    plt = import_pyplot()
    os.makedirs(args.out, exist_ok=True)
    misprint1 = os.path.join(args.data, "fig3_misprint1.csv")
    figure3(plt, read_csv(os.path.join(args.data, needed[0])), args.out,
            read_csv(misprint1) if os.path.exists(misprint1) else None)
    profiles(plt, read_csv(os.path.join(args.data, needed[1])), args.out, "fig4.png",
             "pressure", "pressure p(r)", 4)
    profiles(plt, read_csv(os.path.join(args.data, needed[2])), args.out, "fig5.png",
             "deflection", "deflection w(r)", 5, mark_eq20=True)
    figure7(plt, read_csv(os.path.join(args.data, needed[3])), args.out)
    figure8(plt, read_csv(os.path.join(args.data, needed[4])), args.out)
    for name in ("fig3.png", "fig4.png", "fig5.png", "fig7.png", "fig8.png"):
        print("wrote", os.path.join(args.out, name))


if __name__ == "__main__":
    main()
