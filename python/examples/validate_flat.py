"""A rough flat against BEM: egw.flat_pressure (GW and E-GW laws of the rough flat) against a
periodic boundary-element solution of the same surface (ContactMechanics, load controlled),
nominal pressure p/E* from 1e-6 to 1e-2, at equal mean interfacial separation.

    make python && .venv/bin/pip install contactmechanics
    .venv/bin/python python/examples/validate_flat.py [--grid 256] [--seed 2018]

The BEM gives, at each nominal pressure p, the mean gap u between the rigid rough surface
and the elastic half-space (mean plane of the heights to the deformed counter-face); egw's
separation d is measured from the mean SUMMIT plane, y_s above the mean plane, so egw is
evaluated at d = u - y_s. The surface's GW parameters come from egw.topography on the same
(periodic) map: a flat needs no radius (mu is computed for R = 1, which cancels).
Prints p/E*, u/sigma_s and p_egw/p_BEM for both laws; writes <out>.csv.
"""
from __future__ import annotations

import argparse
import csv
import os
import sys
import warnings

import numpy as np

import egw
from egw import topography as topo


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", type=int, default=256)
    ap.add_argument("--seed", type=int, default=2018)
    ap.add_argument("--out", default="out/validation_flat")
    args = ap.parse_args(argv)
    import ContactMechanics as CM
    from SurfaceTopography import Topography
    from SurfaceTopography.Generation import fourier_synthesis

    n, size, modulus = args.grid, 0.25e-3, 1e9     # ~1 um pixels: 8 per shortest wavelength
    t = fourier_synthesis((n, n), (size, size), hurst=0.8, rms_height=0.2e-6,
                          short_cutoff=8e-6, long_cutoff=100e-6,
                          rng=np.random.default_rng(args.seed))
    heights = np.asarray(t.heights())
    heights = heights - heights.mean()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        params_, report = egw.contact_from_topography(
            Topography(heights, (size, size), periodic=True, unit="m"), radius=None,
            E1=modulus, nu1=0.0, E2=1e300, nu2=0.0)
    # E* of a rigid rough surface on an elastic half-space of contact modulus E*: modulus
    params = {m: params_.replace(model=m, modulus=modulus) for m in ("GW", "E-GW")}
    sigma, y_s = report.sigma, report.y_s
    print(f"surface {n}^2, sigma_s = {sigma:.4e} m, y_s = {y_s:.4e} m, "
          f"mu(R = 1) = {params_.mu:.4g} ({report.estimate})")
    system = CM.make_system(substrate="periodic",
                            surface=Topography(heights, (size, size), periodic=True),
                            young=modulus)
    rows = []
    for p_over_e in 10.0 ** np.arange(-6, -1.5, 0.5):
        force = p_over_e * modulus * size * size
        sol = system.minimize_proxy(external_force=force, pentol=1e-6 * sigma,
                                    maxiter=20000)
        if not sol.success:
            print(f"  p/E* = {p_over_e:.1e}: BEM did not converge ({sol.message})")
            continue
        gap = system.compute_gap(system.disp, sol.offset)
        u = float(np.mean(gap))
        ratio = {m: float(egw.flat_pressure(q, u - y_s)) / (p_over_e * modulus)
                 for m, q in params.items()}
        area = float(np.mean(gap <= 0.0))
        rows.append((p_over_e, u / sigma, area, ratio["GW"], ratio["E-GW"]))
        print(f"  p/E* = {p_over_e:.1e}: u/sigma_s = {u / sigma:6.3f}, contact area "
              f"{area:.2e}, GW/BEM {ratio['GW']:.3f}, E-GW/BEM {ratio['E-GW']:.3f}",
              flush=True)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    with open(args.out + ".csv", "w", newline="") as f:
        f.write(f"# rough flat vs periodic BEM, {n}^2, seed {args.seed}, sigma_s = "
                f"{sigma:.6e} m, y_s = {y_s:.6e} m, E* = {modulus:g} Pa\n")
        w = csv.writer(f)
        w.writerow(["p_over_E", "u_over_sigma", "area_fraction", "GW_over_BEM",
                    "EGW_over_BEM"])
        for r in rows:
            w.writerow([f"{v:.6g}" for v in r])
    print(f"wrote {args.out}.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
