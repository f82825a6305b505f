#!/usr/bin/env python3
"""Draw the coefficient of restitution against impact speed from out/restitution.csv.

    fpm run --profile release --example restitution-curves   # -> out/restitution.csv
    /work/pyref/bin/python tools/plot_restitution.py         # -> doc/figures/restitution.png

Three panels (psi, K, mu varied about psi = 2, K = 0.6, mu = 4): EP-GW e(v) of rough
elastic spheres with elasto-plastic summits (egw `restitution`), with the delta_m = sigma
speed marked, beside the smooth elastic-perfectly-plastic sphere of Thornton (1997) (bulk
plasticity, outside EP-GW).
"""
import argparse
import csv
import os
import sys


def read(path):
    rows = []
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    for r in csv.DictReader(lines):
        rows.append({k: (v if k == "model" else float(v)) for k, v in r.items()})
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default="out/restitution.csv")
    ap.add_argument("--out", default="doc/figures/restitution.png")
    args = ap.parse_args(argv)
    if not os.path.exists(args.data):
        sys.exit(f"plot_restitution.py: no {args.data}: run "
                 "fpm run --example restitution-curves --profile release first")
    try:
        import matplotlib
    except ImportError:  # no make target installs it: say how, not a traceback
        sys.exit("plot_restitution.py: needs matplotlib: .venv/bin/pip install matplotlib, "
                 "then .venv/bin/python tools/plot_restitution.py (README.md)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = read(args.data)
    thornton = [r for r in rows if r["model"] == "Thornton"]
    ep = [r for r in rows if r["model"] == "EP-GW"]
    panels = [("psi", lambda r: r["K"] == 0.6 and r["mu"] == 4.0, r"$\psi$ ($K$ = 0.6, $\mu$ = 4)"),
              ("K", lambda r: r["psi"] == 2.0 and r["mu"] == 4.0, r"$K$ ($\psi$ = 2, $\mu$ = 4)"),
              ("mu", lambda r: r["psi"] == 2.0 and r["K"] == 0.6, r"$\mu$ ($\psi$ = 2, $K$ = 0.6)")]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4), sharey=True)
    for ax, (key, sel, title) in zip(axes, panels):
        sub = [r for r in ep if sel(r)]
        for val in sorted(set(r[key] for r in sub)):
            cur = sorted((r for r in sub if r[key] == val), key=lambda r: r["velocity"])
            line, = ax.semilogx([r["velocity"] for r in cur], [r["e"] for r in cur], "o-", ms=3,
                                label="EP-GW %s = %g" % (key if key != "mu" else "mu", val))
            # the speed where delta_m = sigma (linear in log v between the bracketing points)
            for a, b in zip(cur, cur[1:]):
                if a["delta_m_over_sigma"] < 1.0 <= b["delta_m_over_sigma"]:
                    ax.plot([b["velocity"]], [b["e"]], "s", color=line.get_color(), ms=7,
                            mfc="none")
        ax.semilogx([r["velocity"] for r in thornton], [r["e"] for r in thornton], "k--",
                    label="smooth sphere, Thornton (1997)")
        ax.set_title("varying " + title)
        ax.set_xlabel("impact speed v [m/s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    axes[0].set_ylabel("coefficient of restitution e")
    fig.suptitle("Steel-like spheres R1 = R2 = 1 mm, sigma = 1 um: EP-GW dissipates in the "
                 "summit layer only (squares: first speed with delta_m >= sigma)", fontsize=10)
    fig.tight_layout()
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    tmp = args.out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, args.out)
    print("wrote", args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
