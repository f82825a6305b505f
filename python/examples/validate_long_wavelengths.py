"""A correction for the wavelengths longer than the contact (issue 31, moonshot): the long
part of the roughness as a random waviness of the sphere, the short part as the local
rough-flat law; egw's sphere with it against the full-sphere BEM mean of
validate_flat_laws.py.

Formula (per realisation, per overlap delta_m; sigma = rms height of the whole map):

    a       the contact radius of egw's sphere with the flat law of the WHOLE map at delta_m
            (SolveResult.contact_radius, the uncorrected solve);
    lam_c   = c * 2 a (c = --factor, default 0.5: lam_c = a): the split wavelength,
            q_c = 2 pi / lam_c;
    h_long  = the map's Fourier modes with 0 < |q| < q_c, sigma_l its rms height;
    h_short = h - h_long, law_s its flat law (egw's periodic BEM, or Persson, of h_short);
    F_s(d)  = egw.solve(R, E*, law_s) at overlap d with the mean plane of h_short;
    F_wavy(delta_m) = E_z[ F_s(delta_m + z) ],  z ~ N(0, sigma_l^2)       (Gauss-Hermite)

Assumptions: the long modes are rigid over the contact (a random height z of the surface
under the apex, the same for the whole contact), Gaussian with the map's own variance of
them; their slope and curvature are dropped (the sphere stays a sphere of radius R); the
short modes are a local law, independent of z. delta_m is measured from the mean plane of
the whole map as in the full BEM (the long part has zero mean, so the short part's mean
plane is the same). Two diagnostics come with it: "split" = F_s(delta_m) (the short law
alone, z = 0) and "apex" = F_s(delta_m + h_long(0)) (the realisation's own long-mode height
under the apex, x = 0, between the four middle pixels: deterministic, not a model one can
use without the map's position).

Carried onto egw's BEM law: the per-realisation factor F_wavy / F_full of the --method law
multiplies the realisation's BEM-law force (its logged ratio times its BEM force). With
--method Persson (a second per law) this assumes the correction factor is nearly the same
for both laws (the laws agree within 7 % at these loads, the factor is a ratio of two
solves with the same law); --method BEM computes it with egw's BEM laws of the high-passed
maps (exact, but ~10 s a law on an idle core and ~6 laws a realisation per factor).

Data: the full-sphere BEM forces are NOT recomputed (ContactMechanics, ~90 s a realisation
on two cores). They come from validate_flat_laws.py's stdout (--log: per seed the ratios
egw/BEM of each model at each delta_m, 3 decimals): the realisation's BEM force = egw's
force with the whole map's law of --method (recomputed here, deterministic) / the logged
ratio of that model; and, when --csv is given, its bem_mean_N column is the BEM mean (the
reconstructed mean is printed beside it). For family A (scale separation) only the
published CSV exists (doc/validation/validation_flat_laws_A.csv): the corrected ratio is
then mean(F_wavy) / mean(F_full) * the CSV's mean ratio of the uncorrected law.

    .venv/bin/python python/examples/validate_flat_laws.py --family B --seeds 8 \\
        --out /tmp/valB/validation_flat_laws | tee /tmp/valB/log.txt
    OMP_NUM_THREADS=1 .venv/bin/python python/examples/validate_long_wavelengths.py \\
        --family B --log /tmp/valB/log.txt --csv /tmp/valB/validation_flat_laws_B.csv \\
        --method Persson --factor 0.35 0.5 0.7 1 \\
        --out doc/validation/validation_long_wavelengths
    OMP_NUM_THREADS=1 .venv/bin/python python/examples/validate_long_wavelengths.py \\
        --family A --seeds 8 --csv doc/validation/validation_flat_laws_A.csv \\
        --method Persson --factor 0.35 0.5 0.7 1 \\
        --out doc/validation/validation_long_wavelengths

Writes <out>_<family>_<method>.csv (written to a temporary name, then renamed): per factor
and delta_m/sigma the BEM mean, lam_c, sigma_l/sigma, mean(egw)/mean(BEM) of the --method
law for the whole map ("full"), "split", "wavy" and "apex", and of the BEM law whole and
"wavy" (with the per-realisation ratios' std; family B only); prints them and PASS/MISS
for the moonshot goal ("wavy" within 10 % of the BEM mean at every delta_m >= sigma).
"""
from __future__ import annotations

import argparse
import csv
import os
import re
import sys
import time

import numpy as np

import egw
from egw import topography as topo

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validate_gw import rough_surface  # noqa: E402
from validate_flat_laws import FAMILIES, MODULUS, SIZE, X  # noqa: E402

LOG_MODELS = ("BEM law", "Persson", "GW", "E-GW")
LOG_NAME = {"BEM": "BEM law", "Persson": "Persson"}


def read_log(path, family):
    """validate_flat_laws.py's per-seed lines: {seed: {model: ratios at X}}."""
    pat = re.compile(rf"^{family} seed (\d+) \([^)]*\): (.*)$")
    out = {}
    with open(path) as f:
        for line in f:
            m = pat.match(line.strip())
            if not m:
                continue
            ratios = {}
            for part in m.group(2).split(";"):
                words = part.split()
                k = len(words) - X.size
                ratios[" ".join(words[:k])] = np.array([float(w) for w in words[k:]])
            out[int(m.group(1))] = ratios
    return out


def read_csv(path):
    """The family CSV of validate_flat_laws.py: {column: array}, rows at X."""
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    cols = {name: np.array([float(r[j]) for r in rows[1:]]) for j, name in enumerate(rows[0])}
    if not np.allclose(cols["delta_m_over_sigma"], X):
        raise ValueError(f"{path}: delta_m/sigma {cols['delta_m_over_sigma']} != {X}")
    return cols


def modes(n, size):
    """|q| of the FFT modes of an n x n map of side size, and the integer wavenumbers."""
    k = np.fft.fftfreq(n, 1.0 / n)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    return 2 * np.pi * np.hypot(kx, ky) / size, kx, ky


def split(h, size, lam_c):
    """(h_short, sigma_l, h_long at the apex) for the split wavelength lam_c; the apex is the
    sphere's centre x = 0 of validate_flat_laws.py, between the four middle pixels."""
    n = h.shape[0]
    q, kx, ky = modes(n, size)
    long_ = (q > 0) & (q < 2 * np.pi / lam_c)
    spec = np.fft.fft2(h)
    low = np.where(long_, spec, 0.0)
    h_long = np.real(np.fft.ifft2(low))
    s = n / 2 - 0.5
    z_apex = float(np.real(np.sum(low * np.exp(2j * np.pi * (kx + ky) * s / n)))) / h.size
    return h - h_long, float(np.sqrt(np.mean(h_long ** 2))), z_apex, int(long_.sum())


def law_of(h, size, method, cache, key):
    """The flat law of map h (cached under key: the set of long modes removed)."""
    if key not in cache:
        n = h.shape[0]
        hm = topo.HeightMap(h, size / n, size / n, "m", periodic=True)
        t0 = time.time()
        cache[key] = egw.FlatLaw.from_topography(hm, MODULUS, method, n_threads=1)
        if method == "BEM":
            print(f"  {method} law, {key} long modes removed: {time.time() - t0:.0f} s",
                  file=sys.stderr, flush=True)
    return cache[key]


def realisation(h, fam, method, factors, nodes):
    """egw's forces at X * sigma for one map: full law, and per factor the split, wavy and
    apex forces, sigma_l/sigma and lam_c."""
    rms, radius = fam["rms"], fam["radius"]
    opts = egw.Options(rel_tol=1e-6, n_threads=1)
    overlaps = X * rms
    cache = {}
    full = law_of(h, SIZE, method, cache, 0)
    res = egw.solve(egw.Params(radius=radius, modulus=MODULUS, flat_law=full), overlaps, opts)
    t, w = np.polynomial.hermite.hermgauss(nodes)
    out = {"full": np.asarray(res.force), "a": np.asarray(res.contact_radius)}
    for c in factors:
        r = {k: np.zeros(X.size) for k in ("split", "wavy", "apex", "sigma_l", "lam_c")}
        for i, d in enumerate(overlaps):
            lam_c = c * 2 * out["a"][i]
            hs, sl, za, nlong = split(h, SIZE, lam_c)
            law = full if nlong == 0 else law_of(hs, SIZE, method, cache, nlong)
            p = egw.Params(radius=radius, modulus=MODULUS, flat_law=law)
            d_nodes = np.concatenate(([d, d + za], d + np.sqrt(2) * sl * t))
            f = np.asarray(egw.solve(p, d_nodes, opts).force)
            r["split"][i], r["apex"][i] = f[0], f[1]
            r["wavy"][i] = np.dot(w, f[2:]) / np.sqrt(np.pi)
            r["sigma_l"][i], r["lam_c"][i] = sl / rms, lam_c
        out[c] = r
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--family", default="B", choices=sorted(FAMILIES))
    ap.add_argument("--log", help="validate_flat_laws.py's stdout (per-seed ratios; family B)")
    ap.add_argument("--csv", help="validate_flat_laws.py's CSV of the family (bem_mean_N)")
    ap.add_argument("--method", default="Persson", choices=("BEM", "Persson"))
    ap.add_argument("--factor", type=float, nargs="+", default=[0.5],
                    help="split wavelength / contact diameter 2a")
    ap.add_argument("--nodes", type=int, default=16, help="Gauss-Hermite nodes")
    ap.add_argument("--grid", type=int, default=512)
    ap.add_argument("--seed", type=int, default=2018, help="first seed (without --log)")
    ap.add_argument("--seeds", type=int, default=8, help="realisations (without --log)")
    ap.add_argument("--out", default="out/validation_long_wavelengths")
    args = ap.parse_args(argv)
    fam = FAMILIES[args.family]
    logged = read_log(args.log, args.family) if args.log else {}
    if args.log and not logged:
        ap.error(f"--log {args.log}: no line of family {args.family}")
    if not args.log and not args.csv:
        ap.error("give --log (per-seed BEM forces) or --csv (BEM means)")
    seeds = sorted(logged) if logged else list(range(args.seed, args.seed + args.seeds))
    table = read_csv(args.csv) if args.csv else None
    t0 = time.time()
    runs, bem = [], []
    for seed in seeds:
        h = rough_surface(args.grid, SIZE, fam["rms"], fam["hurst"], fam["short"],
                          fam["long"], seed)
        h = h - h.mean()
        r = realisation(h, fam, args.method, args.factor, args.nodes)
        runs.append(r)
        line = f"seed {seed} ({time.time() - t0:.0f} s):"
        if logged:
            bem.append(r["full"] / logged[seed][LOG_NAME[args.method]])
            line += " full " + " ".join(f"{v:.3f}" for v in r["full"] / bem[-1])
            for c in args.factor:
                line += f"; wavy c={c:g} " + " ".join(f"{v:.3f}" for v in r[c]["wavy"] / bem[-1])
                line += f"; apex c={c:g} " + " ".join(f"{v:.3f}" for v in r[c]["apex"] / bem[-1])
        print(line, flush=True)
    full = np.array([r["full"] for r in runs])
    if logged:
        bem = np.array(bem)
        bem_mean = bem.mean(axis=0)
        if table is not None:
            print("BEM mean from the log / from the CSV: " + " ".join(
                f"{v:.4f}" for v in bem_mean / table["bem_mean_N"]))
            if len(seeds) == 8:
                bem_mean = table["bem_mean_N"]
        # egw's BEM law of the whole map, per realisation, from its logged ratio
        bem_law = np.array([logged[s]["BEM law"] for s in seeds]) * bem
        full_ratio = full.mean(axis=0) / bem_mean
        bem_law_ratio = bem_law.mean(axis=0) / bem_mean
    else:
        full_ratio = table[f"{LOG_NAME[args.method].replace(' ', '_')}_mean_ratio"]
        bem_law_ratio = table["BEM_law_mean_ratio"]
        bem_mean = table["bem_mean_N"]
    rows, misses = [], 0
    for c in args.factor:
        res = {k: np.array([r[c][k] for r in runs]) for k in ("split", "wavy", "apex",
                                                               "sigma_l", "lam_c")}
        scale = full_ratio / full.mean(axis=0)     # = 1 / BEM mean (family A: by the CSV)
        ratio = {k: res[k].mean(axis=0) * scale for k in ("split", "wavy", "apex")}
        # the correction factor wavy / full of the --method law carried onto the BEM law
        if logged:
            bl_wavy = bem_law * res["wavy"] / full
            ratio["bl_wavy"] = bl_wavy.mean(axis=0) / bem_mean
            spread = len(seeds) > 1
            std_full = (bem_law / bem).std(axis=0, ddof=1) if spread else np.nan * X
            std_wavy = (bl_wavy / bem).std(axis=0, ddof=1) if spread else np.nan * X
        else:
            ratio["bl_wavy"] = bem_law_ratio * res["wavy"].mean(axis=0) / full.mean(axis=0)
            std_full = std_wavy = np.nan * X
        print(f"\nfamily {args.family}, split wavelength {c:g} x 2a, {len(seeds)} "
              f"realisations: mean(egw) / mean(BEM) at delta_m / sigma; {args.method} law: "
              f"whole map, split (z = 0), wavy, apex; BEM law: whole map, wavy (the "
              f"{args.method} law's wavy / whole factor)")
        print("   X   lam_c[um] sigma_l/s | full   split   wavy   apex  | BEM law  wavy")
        for i, x in enumerate(X):
            print(f"  {x:4.1f}  {res['lam_c'][:, i].mean() * 1e6:7.1f}  "
                  f"{res['sigma_l'][:, i].mean():7.3f}  | {full_ratio[i]:5.3f}  "
                  f"{ratio['split'][i]:5.3f}  {ratio['wavy'][i]:5.3f}  {ratio['apex'][i]:5.3f}"
                  f" | {bem_law_ratio[i]:5.3f}  {ratio['bl_wavy'][i]:5.3f}")
            rows.append([c, x, bem_mean[i], res["lam_c"][:, i].mean(),
                         res["sigma_l"][:, i].mean(), full_ratio[i], ratio["split"][i],
                         ratio["wavy"][i], ratio["apex"][i], bem_law_ratio[i], std_full[i],
                         ratio["bl_wavy"][i], std_wavy[i]])
        for i, x in enumerate(X):
            if x < 1.0:
                continue
            for name, r0, r1 in ((f"{args.method} law", full_ratio[i], ratio["wavy"][i]),
                                 ("BEM law", bem_law_ratio[i], ratio["bl_wavy"][i])):
                e = abs(r1 - 1)
                misses += e > 0.10
                print(f"  {'PASS' if e <= 0.10 else 'MISS'} c = {c:g}, delta_m {x:4.1f} "
                      f"sigma: {name} wavy {e:.3f} <= 0.10 (uncorrected {abs(r0 - 1):.3f})")
    out = f"{args.out}_{args.family}_{args.method}.csv"
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    tmp = out + ".tmp"
    with open(tmp, "w", newline="") as f:
        f.write(f"# family {args.family}: {fam['label']}; the long wavelengths (> factor x "
                f"2a) as a random waviness z ~ N(0, sigma_l^2) of the sphere, the short as "
                f"the {args.method} flat law; {len(seeds)} realisations (seeds "
                f"{seeds[0]}..{seeds[-1]}), {args.grid}^2; BEM forces from "
                f"{args.log or args.csv}; made by "
                f"python/examples/validate_long_wavelengths.py\n")
        wr = csv.writer(f)
        m = args.method
        wr.writerow(["factor", "delta_m_over_sigma", "bem_mean_N", "lam_c_m",
                     "sigma_l_over_sigma", f"{m}_full_mean_ratio", f"{m}_split_mean_ratio",
                     f"{m}_wavy_mean_ratio", f"{m}_apex_mean_ratio", "BEM_law_full_mean_ratio",
                     "BEM_law_full_ratio_std", "BEM_law_wavy_mean_ratio",
                     "BEM_law_wavy_ratio_std"])
        for row in rows:
            wr.writerow([f"{v:.6g}" for v in row])
    os.replace(tmp, out)
    print(f"wrote {out} ({time.time() - t0:.0f} s)")
    return 1 if misses else 0


if __name__ == "__main__":
    sys.exit(main())
