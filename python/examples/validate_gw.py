"""How close do the GW-type models come to a deterministic contact of the same surface?

Generates a self-affine rough surface, computes its GW parameters with egw.topography
(summit identification and spectral moments), and compares egw's classic GW and E-GW
rough-sphere force-overlap curves with a boundary-element (BEM) solution of the same rough
sphere: the rigid sphere carrying the roughness pressed on an elastic half-space of
contact modulus E*, solved by ContactMechanics (non-periodic FFT half-space, hard-wall
contact). Run on demand (minutes; not part of the test suite):

    make python && .venv/bin/pip install contactmechanics matplotlib
    .venv/bin/python python/examples/validate_gw.py [--grid 512] [--out out/validation]

Writes <out>.csv (overlap, BEM force, egw forces) and <out>.png (force against overlap and
the relative differences); doc/figures/validation_gw.png is this script's output at the
default settings.

Overlap: BEM overlap delta_m is that of the smooth sphere with the MEAN PLANE of the
roughness; egw's delta is measured from the MEAN SUMMIT PLANE, which lies y_s higher, so
delta_egw = delta_m + y_s with y_s the measured mean summit height. GW's sigma is the std of
the summit heights (not the rms height of the surface).
"""
from __future__ import annotations

import argparse
import csv
import os
import sys
import time

import numpy as np

import egw
from egw import topography as topo


def rough_surface(n, size, rms_height, hurst, short_cutoff, long_cutoff, seed):
    from SurfaceTopography.Generation import fourier_synthesis
    t = fourier_synthesis((n, n), (size, size), hurst=hurst, rms_height=rms_height,
                          short_cutoff=short_cutoff, long_cutoff=long_cutoff,
                          rng=np.random.default_rng(seed))
    return np.asarray(t.heights())


def cm_sphere_system(heights, size, radius, modulus):
    """ContactMechanics' non-periodic (free-boundary) FFT half-space of E* = modulus against
    the rigid rough sphere: the paraboloid of radius R, apex at the mean plane of the
    heights, carrying the roughness (heights on a square periodic-sized grid of side size)."""
    import ContactMechanics as CM
    from SurfaceTopography import Topography
    n = heights.shape[0]
    x = (np.arange(n) + 0.5) * size / n - size / 2
    xx, yy = np.meshgrid(x, x, indexing="ij")
    sphere = -(xx ** 2 + yy ** 2) / (2 * radius)
    return CM.make_system(substrate="free",
                          surface=Topography(sphere + heights, (size, size), periodic=False),
                          young=modulus)


def bem_forces(heights, size, radius, modulus, overlaps):
    """BEM force of the rigid rough sphere (apex at the roughness' mean plane) on an elastic
    half-space at each overlap delta_m with that plane."""
    n = heights.shape[0]
    system = cm_sphere_system(heights, size, radius, modulus)
    forces, contact_radii = [], []
    guess = None
    for d in overlaps:
        kwargs = {"offset": d, "pentol": 1e-5 * np.std(heights), "maxiter": 20000}
        if guess is not None:
            kwargs["initial_displacements"] = guess
        sol = system.minimize_proxy(**kwargs)
        if not sol.success:
            raise RuntimeError(f"BEM did not converge at delta_m = {d:g}: {sol.message}")
        guess = system.disp
        forces.append(float(system.compute_normal_force()))
        p = -np.asarray(sol.jac)
        area = p > 0
        contact_radii.append(float(np.sqrt(area.sum() * (size / n) ** 2 / np.pi)))
        print(f"  BEM delta_m = {d: .3e}: force {forces[-1]:.5e}", flush=True)
    return np.array(forces)


def per_realisation_ratios(summit_stats, f_runs, overlaps, radius, modulus):
    """egw / BEM of each realisation with its OWN summit parameters (the question a user
    with one measured surface asks), at the same overlaps with the mean plane."""
    ratios = {}
    for model in ("GW", "E-GW"):
        rows = []
        for s, f_bem in zip(summit_stats, f_runs):
            mu = egw.mu_from_summits(summit_density=s.summit_density,
                                     summit_radius=s.summit_radius, sigma=s.sigma_summits,
                                     radius=radius)
            p = egw.Params(model=model, radius=radius, modulus=modulus,
                           sigma=s.sigma_summits, mu=mu)
            f = egw.solve(p, overlaps + s.mean_summit_height, egw.Options(rel_tol=1e-6)).force
            rows.append(f / f_bem)
        ratios[model] = np.array(rows)
    return ratios


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", type=int, default=512, help="BEM grid points per side")
    ap.add_argument("--surface-grid", type=int, default=1024,
                    help="grid the surfaces are generated on (a multiple of --grid)")
    ap.add_argument("--out", default="out/validation", help="output path without extension")
    ap.add_argument("--seed", type=int, default=2018, help="first random seed")
    ap.add_argument("--seeds", type=int, default=1,
                    help="surface realisations: the BEM force is their mean")
    args = ap.parse_args(argv)
    if args.surface_grid % args.grid or args.grid < 256:
        ap.error("--grid must be >= 256 (4 pixels per shortest wavelength) and divide "
                 "--surface-grid")

    # a 0.5 mm patch, 1 um pixels at 512 points, self-affine H = 0.8 between 100 um and
    # 8 um (8+ pixels per shortest wavelength: summits resolved), rms height 0.2 um;
    # sphere R = 5 mm: contact radius ~100 um at 2 um overlap, well inside the patch
    size, radius, modulus = 0.5e-3, 5e-3, 1e9
    n = args.grid
    seeds = [args.seed + k for k in range(args.seeds)]
    stats = {"summits": [], "spectral": []}
    surfaces = []
    for seed in seeds:
        # one continuous band-limited surface per seed, sampled on the finest grid; its
        # spectrum ends at 8 um, far below the Nyquist limit of a 256+ grid, so every
        # second (fourth) pixel samples the SAME surface: BEM grids compare like for like
        heights = rough_surface(args.surface_grid, size, 0.2e-6, 0.8, 8e-6, 100e-6,
                                seed)[::args.surface_grid // n, ::args.surface_grid // n]
        surface = topo.detrend(topo.HeightMap(heights, size / n, size / n), "mean")
        surfaces.append(surface)
        stats["summits"].append(topo.summit_statistics(surface, periodic=True))
        stats["spectral"].append(topo.mccool(topo.spectral_moments(surface, "fft")))
    # the GW parameters of the ensemble: means over the realisations
    mean = {}
    for label, runs in stats.items():
        mean[label] = {k: float(np.mean([getattr(r, k) for r in runs]))
                       for k in ("sigma_summits", "summit_density", "summit_radius",
                                 "mean_summit_height")}
        alpha = [r.alpha for r in runs if r.alpha is not None]
        print(f"  {runs[0].method}: " + ", ".join(f"{k} {v:.4e}" for k, v in mean[label].items())
              + (f", alpha {np.mean(alpha):.2f}" if alpha else "")
              + f" (mean of {len(runs)} surface{'s' if len(runs) > 1 else ''})")
        for w in runs[0].warnings:
            print(f"  WARNING: {w}")
    print(f"surfaces: {n} x {n} pixels of {size / n:.2e}, "
          f"{np.mean([r.n_summits for r in stats['summits']]):.0f} summits each")

    sigma = mean["summits"]["sigma_summits"]
    overlaps = np.array([-1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 7.0, 10.0]) * sigma
    t0 = time.time()
    f_runs = np.array([bem_forces(s.heights, size, radius, modulus, overlaps)
                       for s in surfaces])
    f_bem = f_runs.mean(axis=0)
    t_bem = time.time() - t0

    curves = {}
    t0 = time.time()
    for label, s in mean.items():
        mu = egw.mu_from_summits(summit_density=s["summit_density"],
                                 summit_radius=s["summit_radius"], sigma=s["sigma_summits"],
                                 radius=radius)
        for model in ("GW", "E-GW"):
            p = egw.Params(model=model, radius=radius, modulus=modulus,
                           sigma=s["sigma_summits"], mu=mu)
            delta = overlaps + s["mean_summit_height"]
            curves[f"{model} ({label})"] = egw.solve(p, delta, egw.Options(rel_tol=1e-6)).force
    t_egw = time.time() - t0
    ratios = per_realisation_ratios(stats["summits"], f_runs, overlaps, radius, modulus)
    hertz = egw.hertz(egw.Params(model="Hertz", radius=radius, modulus=modulus), overlaps)[0]

    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    names = list(curves)
    with open(args.out + ".csv", "w", newline="") as f:
        f.write(f"# egw validation: rough sphere R = {radius}, E* = {modulus}, {n}^2 BEM grid,"
                f" sigma_s = {sigma:.6e}; delta_m = overlap with the roughness mean plane\n")
        w = csv.writer(f)
        w.writerow(["delta_m", "delta_m_over_sigma", "bem", "bem_min", "bem_max"] + names
                   + ["hertz"])
        for i, d in enumerate(overlaps):
            w.writerow([f"{d:.6e}", f"{d / sigma:.3f}", f"{f_bem[i]:.6e}",
                        f"{f_runs[:, i].min():.6e}", f"{f_runs[:, i].max():.6e}"]
                       + [f"{curves[k][i]:.6e}" for k in names] + [f"{hertz[i]:.6e}"])
    if len(seeds) > 1:
        with open(args.out + "_ratios.csv", "w", newline="") as f:
            f.write(f"# egw / BEM per realisation (each with its own summit parameters), "
                    f"{len(seeds)} seeds from {args.seed}, {n}^2 BEM grid\n")
            w = csv.writer(f)
            w.writerow(["delta_m_over_sigma"] + [f"{m}_{q}" for m in ratios
                                                 for q in ("mean", "std", "min", "max")])
            for i, d in enumerate(overlaps):
                w.writerow([f"{d / sigma:.3f}"] + [f"{v:.4f}" for m in ratios for v in (
                    ratios[m][:, i].mean(), ratios[m][:, i].std(ddof=1),
                    ratios[m][:, i].min(), ratios[m][:, i].max())])
        print(f"\negw / BEM per realisation (own parameters), mean ± std [min, max] over "
              f"{len(seeds)}:")
        for i, d in enumerate(overlaps):
            print(f"  {d / sigma:6.2f} " + "   ".join(
                f"{m} {ratios[m][:, i].mean():.3f} ± {ratios[m][:, i].std(ddof=1):.3f} "
                f"[{ratios[m][:, i].min():.3f}, {ratios[m][:, i].max():.3f}]" for m in ratios))
    print(f"\nforce / BEM force (BEM {t_bem:.0f} s, egw {t_egw:.2f} s for {len(names)} curves):")
    print("  delta_m/sigma " + " ".join(f"{k:>18s}" for k in names))
    for i, d in enumerate(overlaps):
        print(f"  {d / sigma:13.2f} " + " ".join(f"{curves[k][i] / f_bem[i]:18.3f}" for k in names))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no chart")
        return 0
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    x = overlaps / sigma
    ax.semilogy(x, f_bem, "ko-", label="BEM (ContactMechanics)"
                + (f", mean of {len(seeds)}" if len(seeds) > 1 else ""))
    if len(seeds) > 1:
        ax.fill_between(x, f_runs.min(axis=0), f_runs.max(axis=0), color="k", alpha=0.15,
                        label="BEM min–max over realisations")
    for k in names:
        ax.semilogy(x, curves[k], "--" if "spectral" in k else "-", label=f"egw {k}")
    ax.semilogy(x[x > 0], hertz[x > 0], ":", color="grey", label="Hertz (smooth)")
    ax.set_xlabel("overlap with the mean plane  δ_m / σ_s")
    ax.set_ylabel("force [N]")
    ax.legend(fontsize=8)
    for k in names:
        bx.plot(x, curves[k] / f_bem - 1, "--" if "spectral" in k else "-", label=k)
    bx.axhline(0, color="k", lw=0.5)
    bx.set_xlabel("δ_m / σ_s")
    bx.set_ylabel("egw / BEM − 1")
    bx.legend(fontsize=8)
    fig.suptitle(f"rough sphere R = {radius * 1e3:g} mm, σ_s = {sigma * 1e6:.3f} µm, "
                 f"{n}² BEM grid: GW-type models against a deterministic BEM")
    fig.tight_layout()
    fig.savefig(args.out + ".png", dpi=110)
    print(f"wrote {args.out}.csv, {args.out}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
