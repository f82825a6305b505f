#!/usr/bin/env python3
"""ContactMechanics' periodic FFT boundary-element solution of a rough flat, as reference
data for egw's own solver (src/egw/laws/flat_bem.f90; test/test_flat_bem.f90).

A seeded self-affine periodic map (numpy only: Gaussian Fourier amplitudes with the power
spectrum C(q) ~ q^(-2(1+H)), H = 0.8, random phases, every wave vector of the grid but
q = 0 up to |k| = n/2, heights scaled to rms 0.01) of n x n pixels on a 1 x 1 square (pixel
1/n) is pressed onto ContactMechanics' PeriodicFFTElasticHalfSpace (contact modulus
E* = 1: `young = 1`, `poisson = 0`) with a hard wall per pixel (NonSmoothContactSystem,
Polonsky-Keer constrained CG `minimize_proxy(external_force=...)`) at six mean pressures
p/E* from 1e-4 to 1e-2 (external_force = p * area, area 1). Tolerances are far tighter than
CM's defaults (pentol = 1e-9 rms height instead of rms/(10 n); forcetol = 1e-12 of the
load), so the comparison tests discretisations, not stopping rules.

Conventions, matched to egw's (read from CM's sources): CM's stiffness is pi E* |q| with q
in cycles per length, i.e. E* |q|/2 with q = 2 pi k/L, the same on every wave vector of the
map; its q = 0 stiffness (a CM choice that shifts the mean displacement and the offset
together) does not change the gap field, so the mean separation is taken as the mean of
CM's gap field `compute_gap(disp, offset)` over all pixels, which is egw's u (the flat's
height above the heights' mean plane, the displacement having zero mean); the area
fraction is CM's `compute_relative_contact_area()` (pixels with a compressive force over
all), egw's (pixels with p > 0)/(n^2).

Writes test/data/bem_contactmechanics_<n>.txt: comment lines '#', then "n pixel modulus
rms", then one line "p u area" per load, then the n x n heights, one line per x index i
(the n values h(i, 1..n)). Usage (from the project root, in the venv with ContactMechanics
and SurfaceTopography from PyPI):
    .venv/bin/python tools/reference/bem_contactmechanics.py [n]   (default 64)
"""
import os
import sys
import time

import numpy as np


def self_affine_map(n, hurst=0.8, rms=0.01, seed=20261128, slope=None):
    """A seeded periodic self-affine map on the unit square, n x n, mean zero, scaled to
    the rms height `rms`, or (if given) to the rms slope `slope` (from the spectrum)."""
    rng = np.random.default_rng(seed)
    kx = np.fft.fftfreq(n, 1.0 / n)
    ky = np.fft.rfftfreq(n, 1.0 / n)
    k = np.sqrt(kx[:, None] ** 2 + ky[None, :] ** 2)
    amp = np.zeros_like(k)
    mask = (k > 0) & (k <= n // 2)
    amp[mask] = k[mask] ** (-(1.0 + hurst))
    spectrum = amp * (rng.standard_normal(k.shape) + 1j * rng.standard_normal(k.shape))
    h = np.fft.irfft2(spectrum, s=(n, n))
    h -= h.mean()
    if slope is not None:
        hq = np.fft.rfft2(h)
        weight = np.where((ky[None, :] == 0) | (2 * ky[None, :] == n), 1.0, 2.0)
        grad2 = np.sum(weight * (2 * np.pi * k) ** 2 * np.abs(hq) ** 2) / n ** 4
        return h * (slope / np.sqrt(grad2))
    return h * (rms / np.sqrt(np.mean(h ** 2)))


def solve_cm(h, loads):
    """CM's periodic hard-wall solution at each mean pressure: (u, area) lists, seconds."""
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import Topography

    n = h.shape[0]
    top = Topography(h, physical_sizes=(1.0, 1.0), periodic=True)
    substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(1.0, 1.0))
    system = NonSmoothContactSystem(substrate, top)
    rms = np.sqrt(np.mean(h ** 2))
    out = []
    disp = None
    t0 = time.perf_counter()
    for p in loads:
        res = system.minimize_proxy(external_force=p * 1.0, pentol=1e-9 * rms,
                                    forcetol=1e-12 * p / n ** 2, maxiter=100000,
                                    initial_displacements=disp)
        if not res.success:
            raise RuntimeError(f"CM did not converge at p = {p}: {res.message}")
        disp = res.x
        gap = system.compute_gap(res.x, res.offset)
        out.append((float(p), float(np.mean(gap)), float(system.compute_relative_contact_area())))
    return out, time.perf_counter() - t0


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 64
    h = self_affine_map(n)
    loads = np.geomspace(1e-4, 1e-2, 6)
    rows, seconds = solve_cm(h, loads)
    path = os.path.join("test", "data", f"bem_contactmechanics_{n}.txt")
    tmp = path + ".tmp"
    from importlib.metadata import version
    with open(tmp, "w") as f:
        f.write(f"# ContactMechanics {version('ContactMechanics')}: periodic FFT half-space "
                "(E* = 1, Fourier stiffness E*|q|/2), hard wall, Polonsky-Keer CG,\n")
        f.write(f"# pentol 1e-9 rms; {n} x {n} seeded self-affine map (H = 0.8), pixel 1/{n}, "
                "made by tools/reference/bem_contactmechanics.py\n")
        f.write("# line 1: n pixel modulus rms; then 6 lines: p/E*  mean separation "
                "(mean of CM's gap field)  contact-area fraction; then the heights, one "
                "line per x index\n")
        f.write(f"{n} {1.0 / n!r} 1.0 {float(np.sqrt(np.mean(h ** 2)))!r}\n")
        for p, u, a in rows:
            f.write(f"{p!r} {u!r} {a!r}\n")
        for i in range(n):
            f.write(" ".join(repr(float(v)) for v in h[i, :]) + "\n")
    os.replace(tmp, path)
    for p, u, a in rows:
        print(f"p/E* = {p:.3e}  u = {u:.6e}  area = {a:.6f}")
    print(f"wrote {path} ({seconds:.2f} s in CM)")


if __name__ == "__main__":
    main()
