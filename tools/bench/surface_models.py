"""Speed against accuracy of the rough sphere's models on a measured surface, judged against
the sphere with the surface's own BEM law (issue 31 item 3; doc/benchmarks.md section 3 (d)).

For one realisation of each surface family of python/examples/validate_flat_laws.py
(512^2, seed 2018): egw.choose_for_surface's error of Hertz, GW, E-GW and Persson against
the BEM law over delta_m in [1, 10] rms heights, each model's set-up time (statistics or
law), its 1-D table's build time at tol 1e-4 and its evaluation time per point (arrays of
1e6 overlaps through Table.eval / egw.hertz; the C loop, one call), and the BEM law's own
cost. The error of each model against the full-sphere BEM (mean of 8 realisations) is read
from doc/validation/validation_flat_laws_<family>.csv when it is there.

    .venv/bin/python tools/bench/surface_models.py [--out doc/bench/surface_models]

One thread (OMP_NUM_THREADS=1 unless set), egw's table cache off (EGW_CACHE_DIR=off unless
set), ~4 min. Writes <out>.csv and <out>.png (error against set-up + build time, one panel
per family; the choice at tol 0.03 printed).
"""
from __future__ import annotations

import argparse
import csv
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

# set-up times are of builds, not of reads from egw's on-disk table cache
os.environ.setdefault("EGW_CACHE_DIR", "off")
# one thread for every model (the BEM law's build scales ~1.9x on 2; libgomp reads this
# when egw's library loads)
os.environ.setdefault("OMP_NUM_THREADS", "1")
import egw  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "examples"))
from validate_flat_laws import FAMILIES, MODULUS, SIZE  # noqa: E402
from validate_gw import rough_surface  # noqa: E402


def eval_ns(fn, x, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn(x)
        best = min(best, time.perf_counter() - t0)
    return best / x.size * 1e9


def full_bem_errors(name):
    """max |egw mean / BEM mean - 1| over delta_m in [1, 10] sigma per model, from the
    validation run's CSV (None when absent)."""
    path = ROOT / "doc" / "validation" / f"validation_flat_laws_{name}.csv"
    if not path.exists():
        return None
    with open(path) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    rows = [r for r in rows if float(r["delta_m_over_sigma"]) >= 1.0]
    out = {}
    for m, col in (("BEM law", "BEM_law"), ("Persson", "Persson"), ("GW", "GW"),
                   ("E-GW", "E-GW")):
        out[m] = max(abs(float(r[f"{col}_mean_ratio"]) - 1) for r in rows)
    return out


def plot(rows, out):
    """The chart of rows (as written to the CSV) -> out.png."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no figure")
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    floor = 1e-4   # the truth's own error (0) is drawn here
    for ax, name in zip(axes, FAMILIES):
        fam_rows = [r for r in rows if r["family"] == name]
        for r in fam_rows:
            cost = max(r["setup_s"] + r["table_build_s"], 1e-4)
            truth = r["model"] == "BEM law"
            err = floor if truth else max(r["error_vs_bem_law"], floor)
            ax.loglog(cost, err, "*" if truth else "o", ms=11 if truth else 7)
            ax.annotate(r["model"] + (" (the truth)" if truth else ""), (cost, err),
                        textcoords="offset points", xytext=(-40 if truth else 5, 5))
            if np.isfinite(r["error_vs_full_bem"]):
                ax.loglog(cost, max(r["error_vs_full_bem"], floor), "kx")
        for tol in (0.03, 0.1):
            ax.axhline(tol, color="0.5", lw=0.8, ls="--")
            ax.text(0.02, tol * 1.08, f"tol {tol:g}", transform=ax.get_yaxis_transform(),
                    fontsize=8, color="0.4")
        ax.set_title(f"family {name}: {FAMILIES[name]['label']}", fontsize=9)
        ax.set_xlabel("set-up + 1-D table build [s] (one thread)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max |F / F_true - 1|, delta_m in [1, 10] sigma")
    fig.suptitle("Models of a measured surface's rough sphere (o: against the sphere with "
                 "the surface's BEM law; x: against the full-sphere BEM, mean of the "
                 "validation's realisations)", fontsize=8.5)
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out + ".png")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", type=int, default=512)
    ap.add_argument("--seed", type=int, default=2018)
    ap.add_argument("--out", default="out/bench/surface_models")
    ap.add_argument("--plot-only", action="store_true", help="redraw <out>.png from <out>.csv")
    args = ap.parse_args(argv)
    if args.plot_only:
        with open(args.out + ".csv") as f:
            rows = [{k: (v if k in ("family", "model") else float(v)) for k, v in r.items()}
                    for r in csv.DictReader(line for line in f if not line.startswith("#"))]
        plot(rows, args.out)
        print(f"wrote {args.out}.png")
        return 0
    n = args.grid
    rows = []
    for name, fam in FAMILIES.items():
        h = rough_surface(n, SIZE, fam["rms"], fam["hurst"], fam["short"], fam["long"],
                          args.seed)
        h = h - h.mean()
        top = egw.topography.HeightMap(h, SIZE / n, SIZE / n, "m", periodic=True)
        t0 = time.perf_counter()
        truth = egw.FlatLaw.from_topography(top, MODULUS, "BEM")
        t_truth = time.perf_counter() - t0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            c = egw.choose_for_surface(top, radius=fam["radius"], modulus=MODULUS, tol=0.03,
                                       delta_min_sigma=1.0, delta_max_sigma=10.0,
                                       truth=truth)
        sigma = truth.length
        x = np.linspace(-2 * sigma, 10 * sigma, 1_000_000)
        full = full_bem_errors(name)
        for m in c.candidates:
            setup = t_truth if m.model == "BEM law" else m.seconds
            if m.model == "Hertz":
                build, ns = 0.0, eval_ns(lambda d: egw.hertz(m.params, d), x)
            else:
                t0 = time.perf_counter()
                t = egw.Table.build(m.params, x[0] + m.y_s, x[-1] + m.y_s, 1e-4)
                build = time.perf_counter() - t0
                ns = eval_ns(lambda d: t.eval(d + m.y_s), x)
            rows.append(dict(family=name, model=m.model, error_vs_bem_law=m.error,
                             error_vs_full_bem=(full or {}).get(m.model, float("nan")),
                             setup_s=setup, table_build_s=build, eval_ns=ns))
            print(f"{name} {m.model:8s} error vs BEM law {m.error:.3g}, vs full BEM "
                  f"{rows[-1]['error_vs_full_bem']:.3g}; set-up {setup:.3g} s, table "
                  f"{build:.3g} s, {ns:.1f} ns/point", flush=True)
        print(f"{name}: choice at tol 0.03: {c.reason}")
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    tmp = args.out + ".csv.tmp"
    with open(tmp, "w", newline="") as f:
        f.write(f"# tools/bench/surface_models.py --grid {n} --seed {args.seed}; "
                f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
                f"{open('/proc/loadavg').read().split()[0]}\n")
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    os.replace(tmp, args.out + ".csv")
    plot(rows, args.out)
    print(f"wrote {args.out}.csv and .png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
