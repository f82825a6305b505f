"""From a measured height map to Greenwood-Williamson parameters.

Reads a height map (plain-text matrix, CSV, numpy .npy), removes its mean plane, and
computes the GW statistics two ways:

* spectral (Nayak 1971; McCool 1986): the profile moments m0 = <z^2>, m2 = <z'^2>,
  m4 = <z''^2> (averaged over the x and y directions), the bandwidth parameter
  alpha = m0 m4/m2^2, and from them the summit density eta = m4/(6 pi sqrt(3) m2), the mean
  summit radius beta = (3/8) sqrt(pi/m4), the std of summit heights
  sigma_s = sqrt((1 - 0.8968/alpha) m0) and the offset of the mean summit height above the
  mean plane y_s = 4 sqrt(m0/(pi alpha));
* by summit identification: pixels higher than their 8 neighbours; eta = count/area,
  sigma_s = their height std, beta = 1/mean(kappa) with kappa = -(z_xx + z_yy)/2 the mean
  curvature at the summit (central differences).

Derivatives: 'fft' (spectral, exact for a periodic band-limited map such as a synthetic
surface) or 'difference' (central differences, for measured, non-periodic maps).
The contact parameters (mu for a sphere radius R, psi for E*, H) are computed by the C
library (egw_mu_from_summits, egw_psi_from_hardness); GW's assumptions are flagged when
alpha is small or few summits were found.
"""
from __future__ import annotations

import argparse
import ctypes
import math
import os
import sys
import warnings
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

import numpy as np

from ._capi import lib
from .core import check, mu_from_summits

#: below this bandwidth parameter McCool's summit statistics are poor (sigma_s^2 loses
#: more than 10 % against m0: 0.8968/alpha > 0.1) — GW's isolated-summit picture is
#: questionable; Nayak's asymptotics assume alpha >> 1.
ALPHA_WARN = 8.968
#: fewer summits than this give a summit density with a >10 % statistical error (1/sqrt(N)).
SUMMITS_WARN = 100


class TopographyWarning(UserWarning):
    """GW's assumptions are poor for this surface (small alpha, few summits)."""


@dataclass
class HeightMap:
    """Heights z[i, j] (rows along y, columns along x) on a grid of pixel size
    (dx, dy) [length]."""
    heights: np.ndarray
    dx: float
    dy: float

    @property
    def area(self) -> float:
        ny, nx = self.heights.shape
        return nx * self.dx * ny * self.dy


@dataclass
class Moments:
    """Profile spectral moments m0 [length^2], m2 [-], m4 [1/length^2] (averaged over
    x and y), and their directional parts."""
    m0: float
    m2: float
    m4: float
    m2_xy: Tuple[float, float] = (math.nan, math.nan)
    m4_xy: Tuple[float, float] = (math.nan, math.nan)

    @property
    def alpha(self) -> float:
        return self.m0 * self.m4 / self.m2 ** 2

    def __add__(self, other: "Moments") -> "Moments":
        """Moments of the sum surface of two independent surfaces (they add)."""
        return Moments(self.m0 + other.m0, self.m2 + other.m2, self.m4 + other.m4,
                       tuple(a + b for a, b in zip(self.m2_xy, other.m2_xy)),
                       tuple(a + b for a, b in zip(self.m4_xy, other.m4_xy)))


@dataclass
class SummitStatistics:
    """GW parameters: summit density eta [1/length^2], mean summit radius beta [length],
    std of summit heights sigma_s [length], rms height of the surface sigma_z [length],
    and (summit identification) the number of summits found."""
    method: str
    summit_density: float
    summit_radius: float
    sigma_summits: float
    sigma_surface: float
    n_summits: Optional[int] = None
    alpha: Optional[float] = None
    mean_summit_height: Optional[float] = None
    warnings: List[str] = field(default_factory=list)


def read_height_map(path: str, pixel_size: float | Tuple[float, float] = 1.0) -> HeightMap:
    """Read a height map: `.npy` (numpy), `.csv` (comma-separated rows) or a plain-text
    matrix (whitespace-separated rows); '#' lines are comments. pixel_size: dx or (dx, dy)."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".npy":
        z = np.load(path, allow_pickle=False)
    else:
        z = np.loadtxt(path, delimiter="," if ext == ".csv" else None, comments="#", ndmin=2)
    z = np.asarray(z, dtype=np.float64)
    if z.ndim != 2 or min(z.shape) < 3:
        raise ValueError(f"{path}: a height map must be a 2-D matrix of at least 3 x 3 "
                         f"values (got shape {z.shape})")
    if not np.all(np.isfinite(z)):
        raise ValueError(f"{path}: the height map has {np.count_nonzero(~np.isfinite(z))} "
                         "non-finite values (fill or crop missing data first)")
    dx, dy = (pixel_size, pixel_size) if np.isscalar(pixel_size) else pixel_size
    if not (dx > 0 and dy > 0 and math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError(f"pixel_size = {pixel_size}: must be finite and > 0")
    return HeightMap(z, float(dx), float(dy))


def detrend(surface: HeightMap, mode: str = "plane") -> HeightMap:
    """Remove the mean ('mean') or the least-squares plane ('plane') of the heights."""
    z = surface.heights
    if mode == "mean":
        return HeightMap(z - z.mean(), surface.dx, surface.dy)
    if mode != "plane":
        raise ValueError(f"mode = {mode!r}: must be 'plane' or 'mean'")
    ny, nx = z.shape
    y, x = np.mgrid[0:ny, 0:nx]
    a = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return HeightMap(z - (a @ coef).reshape(z.shape), surface.dx, surface.dy)


def _derivatives(surface: HeightMap, method: str):
    """(z_x, z_y, z_xx, z_yy) on the grid (interior only for 'difference')."""
    z, dx, dy = surface.heights, surface.dx, surface.dy
    if method == "fft":
        ny, nx = z.shape
        qx = 2 * np.pi * np.fft.fftfreq(nx, dx)
        qy = 2 * np.pi * np.fft.fftfreq(ny, dy)
        zh = np.fft.fft2(z)
        if nx % 2 == 0:  # the Nyquist mode has no sign: drop it from odd derivatives
            qx_odd = qx.copy(); qx_odd[nx // 2] = 0.0
        else:
            qx_odd = qx
        if ny % 2 == 0:
            qy_odd = qy.copy(); qy_odd[ny // 2] = 0.0
        else:
            qy_odd = qy
        zx = np.fft.ifft2(1j * qx_odd[None, :] * zh).real
        zy = np.fft.ifft2(1j * qy_odd[:, None] * zh).real
        zxx = np.fft.ifft2(-(qx ** 2)[None, :] * zh).real
        zyy = np.fft.ifft2(-(qy ** 2)[:, None] * zh).real
        return zx, zy, zxx, zyy
    if method == "difference":
        c = z[1:-1, 1:-1]
        zx = (z[1:-1, 2:] - z[1:-1, :-2]) / (2 * dx)
        zy = (z[2:, 1:-1] - z[:-2, 1:-1]) / (2 * dy)
        zxx = (z[1:-1, 2:] - 2 * c + z[1:-1, :-2]) / dx ** 2
        zyy = (z[2:, 1:-1] - 2 * c + z[:-2, 1:-1]) / dy ** 2
        return zx, zy, zxx, zyy
    raise ValueError(f"method = {method!r}: must be 'fft' or 'difference'")


def spectral_moments(surface: HeightMap, method: str = "fft") -> Moments:
    """Profile moments m0, m2, m4 of a (detrended) height map, averaged over the x and y
    directions (for an isotropic surface they are the profile moments in any direction)."""
    z = surface.heights
    zx, zy, zxx, zyy = _derivatives(surface, method)
    m0 = float(np.mean((z - z.mean()) ** 2))
    m2x, m2y = float(np.mean(zx ** 2)), float(np.mean(zy ** 2))
    m4x, m4y = float(np.mean(zxx ** 2)), float(np.mean(zyy ** 2))
    return Moments(m0, 0.5 * (m2x + m2y), 0.5 * (m4x + m4y), (m2x, m2y), (m4x, m4y))


def mccool(moments: Moments) -> SummitStatistics:
    """GW summit statistics from the spectral moments (Nayak 1971, McCool 1986)."""
    m0, m2, m4 = moments.m0, moments.m2, moments.m4
    if not (m0 > 0 and m2 > 0 and m4 > 0):
        raise ValueError(f"spectral moments m0 = {m0}, m2 = {m2}, m4 = {m4}: all must be > 0")
    alpha = moments.alpha
    notes = []
    if alpha < ALPHA_WARN:
        notes.append(f"bandwidth parameter alpha = {alpha:.3g} < {ALPHA_WARN}: summit "
                     "statistics from the moments are poor (GW assumes alpha >> 1)")
    ratio = 1.0 - 0.8968 / alpha
    sigma_s = math.sqrt(max(ratio, 0.0) * m0)
    return SummitStatistics("spectral (McCool)", m4 / (6 * math.pi * math.sqrt(3) * m2),
                            0.375 * math.sqrt(math.pi / m4), sigma_s, math.sqrt(m0),
                            alpha=alpha, mean_summit_height=4 * math.sqrt(m0 / (math.pi * alpha)),
                            warnings=notes)


def identify_summits(surface: HeightMap, periodic: bool = False):
    """Indices (iy, ix) of the 8-neighbour summits: pixels strictly higher than all eight
    neighbours (the border rows/columns are skipped unless periodic)."""
    z = surface.heights
    if periodic:
        is_max = np.ones(z.shape, dtype=bool)
        for sy in (-1, 0, 1):
            for sx in (-1, 0, 1):
                if sy or sx:
                    is_max &= z > np.roll(np.roll(z, sy, axis=0), sx, axis=1)
        return np.nonzero(is_max)
    c = z[1:-1, 1:-1]
    is_max = np.ones(c.shape, dtype=bool)
    ny, nx = z.shape
    for sy in (-1, 0, 1):
        for sx in (-1, 0, 1):
            if sy or sx:
                is_max &= c > z[1 + sy:ny - 1 + sy, 1 + sx:nx - 1 + sx]
    iy, ix = np.nonzero(is_max)
    return iy + 1, ix + 1


def summit_statistics(surface: HeightMap, periodic: bool = False) -> SummitStatistics:
    """GW parameters by 8-neighbour summit identification on the detrended map."""
    z, dx, dy = surface.heights, surface.dx, surface.dy
    iy, ix = identify_summits(surface, periodic)
    n = iy.size
    ny, nx = z.shape
    area = (nx * dx * ny * dy) if periodic else ((nx - 2) * dx * (ny - 2) * dy)
    notes = []
    if n < SUMMITS_WARN:
        notes.append(f"only {n} summits found (< {SUMMITS_WARN}): the summit statistics "
                     "carry more than 10 % statistical error")
    if n < 2:
        raise ValueError(f"{n} summits found: the map is too small or too smooth")
    zc = z - z.mean()
    zs = zc[iy, ix]
    up, down = (iy + 1) % ny, (iy - 1) % ny
    right, left = (ix + 1) % nx, (ix - 1) % nx
    zxx = (zc[iy, right] - 2 * zs + zc[iy, left]) / dx ** 2
    zyy = (zc[up, ix] - 2 * zs + zc[down, ix]) / dy ** 2
    kappa = -0.5 * (zxx + zyy)
    return SummitStatistics("summit identification (8 neighbours)", n / area,
                            1.0 / float(np.mean(kappa)), float(np.std(zs)),
                            float(np.sqrt(np.mean(zc ** 2))), n_summits=n,
                            mean_summit_height=float(np.mean(zs)), warnings=notes)


def sum_surface(a: HeightMap, b: HeightMap) -> HeightMap:
    """The sum surface z1 + z2 of two maps on the same grid (GW's equivalent rough
    surface against a smooth one; its moments are the sums for independent surfaces)."""
    if a.heights.shape != b.heights.shape or (a.dx, a.dy) != (b.dx, b.dy):
        raise ValueError("sum_surface: the two maps need the same shape and pixel size")
    return HeightMap(a.heights + b.heights, a.dx, a.dy)


def psi_from_hardness(modulus: float, hardness: float, sigma: float, summit_radius: float,
                      hardness_coeff: float = 0.6) -> float:
    """The paper's plasticity index psi = 4 E*/(3 pi K H) sqrt(sigma/beta)."""
    psi = ctypes.c_double()
    check(lib.egw_psi_from_hardness(float(modulus), float(hardness), float(hardness_coeff),
                                    float(sigma), float(summit_radius), ctypes.byref(psi)))
    return psi.value


def _report(stats: SummitStatistics, radius, modulus, hardness, k) -> List[str]:
    lines = [f"{stats.method}:",
             f"  summit density eta     {stats.summit_density:.6g} per unit area",
             f"  summit radius beta     {stats.summit_radius:.6g}",
             f"  summit height std      {stats.sigma_summits:.6g}",
             f"  surface rms height     {stats.sigma_surface:.6g}"]
    if stats.n_summits is not None:
        lines.append(f"  summits found          {stats.n_summits}")
    if stats.alpha is not None:
        lines.append(f"  bandwidth alpha        {stats.alpha:.6g}")
    if radius is not None:
        mu = mu_from_summits(stats.summit_density, stats.summit_radius, stats.sigma_summits,
                             radius)
        lines.append(f"  mu (R = {radius:g})        {mu:.6g}")
    if modulus is not None and hardness is not None:
        psi = psi_from_hardness(modulus, hardness, stats.sigma_summits, stats.summit_radius, k)
        lines.append(f"  psi (E* = {modulus:g}, H = {hardness:g}, K = {k:g})  {psi:.6g}")
    lines += [f"  WARNING: {w}" for w in stats.warnings]
    return lines


def main(argv: Optional[Sequence[str]] = None) -> int:
    """egw-topo: GW parameters of one height map, or of the sum surface of two."""
    ap = argparse.ArgumentParser(
        prog="egw-topo", description="Greenwood-Williamson parameters (sigma, eta, beta) of "
        "a measured height map, by summit identification and by spectral moments.")
    ap.add_argument("maps", nargs="+", help="height map(s): .npy, .csv or a text matrix; "
                    "two maps: their sum surface")
    ap.add_argument("--pixel-size", type=float, nargs="+", required=True, metavar="D",
                    help="pixel size dx [dy] in the length unit of the heights")
    ap.add_argument("--radius", type=float, help="equivalent sphere radius R: print mu")
    ap.add_argument("--modulus", type=float, help="effective modulus E*: with --hardness, psi")
    ap.add_argument("--hardness", type=float, help="hardness H (units of --modulus)")
    ap.add_argument("--K", type=float, default=0.6, help="ZMC hardness coefficient (0.6)")
    ap.add_argument("--derivatives", choices=["difference", "fft"], default="difference",
                    help="derivatives for the moments: central differences (default, any "
                    "map) or FFT (periodic maps)")
    ap.add_argument("--periodic", action="store_true", help="the map is periodic")
    args = ap.parse_args(argv)
    try:
        if len(args.maps) > 2:
            raise ValueError("give one height map, or two for their sum surface")
        if len(args.pixel_size) > 2:
            raise ValueError("--pixel-size takes dx or dx dy")
        pixel = tuple(args.pixel_size) if len(args.pixel_size) == 2 else args.pixel_size[0]
        maps = [detrend(read_height_map(m, pixel)) for m in args.maps]
        surface = maps[0] if len(maps) == 1 else sum_surface(*maps)
        spectral = mccool(spectral_moments(surface, args.derivatives))
        summits = summit_statistics(surface, args.periodic)
        print(f"egw-topo: {' + '.join(args.maps)}, {surface.heights.shape[1]} x "
              f"{surface.heights.shape[0]} pixels")
        for stats in (summits, spectral):
            print("\n".join(_report(stats, args.radius, args.modulus, args.hardness, args.K)))
    except (ValueError, OSError) as exc:
        print(f"egw-topo: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
