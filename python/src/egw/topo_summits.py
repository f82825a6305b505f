"""Summit statistics of a height map, GW's parameters: from the spectral moments (McCool 1986)
and by identifying summits (8 neighbours), with the limits where GW's picture is poor."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from .errors import _flag
from .topo_maps import HeightMap
from .topo_spectra import Moments


#: below this bandwidth parameter McCool's summit statistics are poor (sigma_s^2 loses
#: more than 10 % against m0: 0.8968/alpha > 0.1) — GW's isolated-summit picture is
#: questionable; Nayak's asymptotics assume alpha >> 1.
ALPHA_WARN = 8.968


#: fewer summits than this give a summit density with a >10 % statistical error (1/sqrt(N)).
SUMMITS_WARN = 100


class TopographyWarning(UserWarning):
    """GW's assumptions are poor for this surface (small alpha, few summits)."""


@dataclass
class SummitStatistics:
    """GW parameters of a surface, by one method.

    Attributes
    ----------
    method : str
        How they were found (summit identification or spectral).
    summit_density : float
        eta [1/length^2].
    summit_radius : float
        Mean summit radius beta [length].
    sigma_summits : float
        Std of the summit heights sigma_s [length] (GW's sigma).
    sigma_surface : float
        Rms height of the surface [length].
    n_summits : int or None
        Summits found (summit identification only).
    alpha : float or None
        Nayak's bandwidth parameter (spectral only).
    mean_summit_height : float or None
        Mean summit height above the mean plane of the heights [length] (y_s: an overlap
        delta_m from the mean plane is delta = delta_m + y_s for GW's models).
    warnings : list of str
        Where GW's assumptions are poor.
    """
    method: str
    summit_density: float
    summit_radius: float
    sigma_summits: float
    sigma_surface: float
    n_summits: Optional[int] = None
    alpha: Optional[float] = None
    mean_summit_height: Optional[float] = None
    warnings: List[str] = field(default_factory=list)


def mccool(moments: Moments) -> SummitStatistics:
    """GW summit statistics from the spectral moments (Nayak 1971, McCool 1986):
    eta = m4/(6 pi sqrt(3) m2), beta = (3/8) sqrt(pi/m4), sigma_s^2 = (1 - 0.8968/alpha)
    m0, y_s = 4 sqrt(m0/(pi alpha)).

    Parameters
    ----------
    moments : Moments
        The profile moments (all > 0).

    Returns
    -------
    SummitStatistics
        With alpha and mean_summit_height (y_s); a warning note when alpha < ALPHA_WARN.

    Raises
    ------
    ValueError
        A moment that is not > 0.
    """
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
    """The 8-neighbour summits: pixels strictly higher than all eight neighbours.

    Parameters
    ----------
    surface : HeightMap
        The map.
    periodic : bool
        Neighbours across the edges (else the border rows and columns are skipped).

    Returns
    -------
    iy, ix : ndarray of int
        Row and column indices of the summits.

    Raises
    ------
    TypeError
        periodic not True or False ("no" would have meant True).
    """
    z = surface.heights
    periodic = _flag("periodic", periodic)
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
    """GW parameters by 8-neighbour summit identification on the detrended map: eta =
    count/area, sigma_s = std of their heights, beta = 1/mean(kappa) with kappa the mean
    curvature -(z_xx + z_yy)/2 at each summit (central differences).

    Parameters
    ----------
    surface : HeightMap
        The detrended map.
    periodic : bool
        Summits and curvatures across the edges.

    Returns
    -------
    SummitStatistics
        With n_summits and mean_summit_height (y_s, above the mean plane); a warning note
        for fewer than SUMMITS_WARN summits. Summits and curvatures are those the pixel
        resolves: with roughness down to the pixel, they depend on the pixel size.

    Raises
    ------
    ValueError
        Fewer than 2 summits.
    """
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
