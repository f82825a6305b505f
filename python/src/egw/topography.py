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

Both estimates see the surface only down to the pixel. On a map rough down to the pixel
(no short-wavelength cut-off in the data) m2 and m4 grow as the pixel shrinks, and eta,
beta (so mu, psi) are those of the sampling: analyse() coarse-grains the map by 2 and
warns when the spectral eta or beta changes by more than RESOLUTION_TOL. Then cut the map
off at a physical short-wavelength limit (coarse_grain, a low-pass filter) until they stop
changing, or use a contact law that needs no summit statistics (Persson's theory, a
boundary-element rough-flat law).
"""
from __future__ import annotations

import argparse
import ctypes
import dataclasses
import json
import math
import os
import sys
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._capi import lib
from .errors import check
from .params import Params
from ._calls import _keyword_only
from .functions import effective_modulus, mu_from_summits

#: below this bandwidth parameter McCool's summit statistics are poor (sigma_s^2 loses
#: more than 10 % against m0: 0.8968/alpha > 0.1) — GW's isolated-summit picture is
#: questionable; Nayak's asymptotics assume alpha >> 1.
ALPHA_WARN = 8.968
#: fewer summits than this give a summit density with a >10 % statistical error (1/sqrt(N)).
SUMMITS_WARN = 100


class TopographyWarning(UserWarning):
    """GW's assumptions are poor for this surface (small alpha, few summits)."""


#: length units a map may carry, in metres
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9,
                "pm": 1e-12, "A": 1e-10, "Å": 1e-10, "cm": 1e-2, "km": 1e3}


@dataclass
class HeightMap:
    """A height map: heights z[i, j] (rows along y, columns along x) on a grid of pixel
    size (dx, dy).

    Attributes
    ----------
    heights : ndarray, shape (ny, nx)
        Heights [unit].
    dx, dy : float
        Pixel sizes [unit], > 0.
    unit : str or None
        The length unit of the heights AND the pixel sizes (a key of LENGTH_UNITS);
        None = unknown (the contact functions refuse such a map).
    periodic : bool
        The map is one period of a periodic surface (detrended by its mean only, FFT
        derivatives, summits found across the edges).
    """
    heights: np.ndarray
    dx: float
    dy: float
    unit: Optional[str] = None
    periodic: bool = False

    def to_metres(self) -> "HeightMap":
        """The same map in metres.

        Returns
        -------
        HeightMap
            Heights and pixel sizes scaled to metres, unit 'm'.

        Raises
        ------
        ValueError
            The map has no unit or an unknown one.
        """
        factor = _unit_factor(self.unit)
        return HeightMap(self.heights * factor, self.dx * factor, self.dy * factor, "m",
                         self.periodic)

    @property
    def area(self) -> float:
        """Area of the map [unit^2]."""
        ny, nx = self.heights.shape
        return nx * self.dx * ny * self.dy


@dataclass
class Moments:
    """Profile spectral moments of a surface (averaged over the x and y directions).

    Attributes
    ----------
    m0 : float
        Variance of the heights [length^2].
    m2 : float
        Variance of the slopes [-].
    m4 : float
        Variance of the curvatures [1/length^2].
    m2_xy, m4_xy : (float, float)
        m2 and m4 along x and along y (NaN when not known).
    """
    m0: float
    m2: float
    m4: float
    m2_xy: Tuple[float, float] = (math.nan, math.nan)
    m4_xy: Tuple[float, float] = (math.nan, math.nan)

    @property
    def alpha(self) -> float:
        """Nayak's bandwidth parameter alpha = m0 m4/m2^2."""
        return self.m0 * self.m4 / self.m2 ** 2

    def __add__(self, other: "Moments") -> "Moments":
        """Moments of the sum surface of two independent surfaces (they add)."""
        return Moments(self.m0 + other.m0, self.m2 + other.m2, self.m4 + other.m4,
                       tuple(a + b for a, b in zip(self.m2_xy, other.m2_xy)),
                       tuple(a + b for a, b in zip(self.m4_xy, other.m4_xy)))


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


def read_height_map(path: str, pixel_size: Union[float, Tuple[float, float]] = 1.0,
                    unit: Optional[str] = None, periodic: bool = False) -> HeightMap:
    """Read a height map: `.npy` (numpy), `.csv` (comma-separated rows) or a plain-text
    matrix (whitespace-separated rows); '#' lines are comments. Instrument formats:
    :func:`height_map` (through SurfaceTopography).

    Parameters
    ----------
    path : str
        The file.
    pixel_size : float or (dx, dy)
        In the unit of the heights.
    unit : str, optional
        Recorded on the map (None = unknown: the contact functions refuse it).
    periodic : bool
        The map is one period of a periodic surface.

    Returns
    -------
    HeightMap

    Raises
    ------
    ValueError
        Not a 2-D matrix of at least 3 x 3, NaN or infinite pixels, a bad pixel size or
        an unknown unit.
    OSError
        The file cannot be read.
    """
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
    _check_scales(z, float(dx), float(dy), path)
    _check_unit(unit)
    return HeightMap(z, float(dx), float(dy), unit, bool(periodic))


def detrend(surface: HeightMap, mode: Optional[str] = None) -> HeightMap:
    """Remove the mean ('mean') or the least-squares plane ('plane') of the heights.

    Parameters
    ----------
    surface : HeightMap
        The map.
    mode : {'mean', 'plane'}, optional
        None (default): 'mean' for a periodic map (a plane would break its periodicity
        and inflate the spectral moments), 'plane' otherwise; the shared default of the
        CLI and Python (see DEFAULTS).

    Returns
    -------
    HeightMap
        The detrended map (the same grid, unit and periodicity).

    Raises
    ------
    ValueError
        Another mode.
    """
    mode = mode or default_detrend(surface.periodic)
    z = surface.heights
    if mode == "mean":
        return dataclasses.replace(surface, heights=z - z.mean())
    if mode != "plane":
        raise ValueError(f"mode = {mode!r}: must be 'plane' or 'mean'")
    ny, nx = z.shape
    y, x = np.mgrid[0:ny, 0:nx]
    a = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return dataclasses.replace(surface, heights=z - (a @ coef).reshape(z.shape))


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


def spectral_moments(surface: HeightMap, method: Optional[str] = None) -> Moments:
    """Profile moments m0, m2, m4 of a (detrended) height map, averaged over the x and y
    directions (for an isotropic surface they are the profile moments in any direction).

    Parameters
    ----------
    surface : HeightMap
        The detrended map.
    method : {'fft', 'difference'}, optional
        'fft' (exact for a periodic band-limited map) or 'difference' (central
        differences, any map); None: 'fft' for a periodic map, else 'difference'
        (DEFAULTS).

    Returns
    -------
    Moments
        In the map's unit. Both methods resolve nothing finer than the pixel: on a map
        whose roughness continues down to the pixel, m2 and m4 (and so eta, beta) depend
        on the pixel size (doc/parameters.md).

    Raises
    ------
    ValueError
        Another method.
    """
    method = method or default_derivatives(surface.periodic)
    z = surface.heights
    zx, zy, zxx, zyy = _derivatives(surface, method)
    m0 = float(np.mean((z - z.mean()) ** 2))
    m2x, m2y = float(np.mean(zx ** 2)), float(np.mean(zy ** 2))
    m4x, m4y = float(np.mean(zxx ** 2)), float(np.mean(zyy ** 2))
    return Moments(m0, 0.5 * (m2x + m2y), 0.5 * (m4x + m4y), (m2x, m2y), (m4x, m4y))


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
    """
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


def sum_surface(a: HeightMap, b: HeightMap) -> HeightMap:
    """The sum surface z1 + z2 of two maps on the same grid (GW's equivalent rough
    surface against a smooth one; its moments are the sums for independent surfaces).

    Parameters
    ----------
    a, b : HeightMap
        Maps of the same shape, pixel size and unit.

    Returns
    -------
    HeightMap
        Periodic when both are.

    Raises
    ------
    ValueError
        Different shapes, pixel sizes or units.
    """
    if a.heights.shape != b.heights.shape or (a.dx, a.dy) != (b.dx, b.dy):
        raise ValueError("sum_surface: the two maps need the same shape and pixel size")
    if a.unit != b.unit:
        raise ValueError(f"sum_surface: the maps are in {a.unit!r} and {b.unit!r}: "
                         "convert one (HeightMap.to_metres)")
    return HeightMap(a.heights + b.heights, a.dx, a.dy, a.unit, a.periodic and b.periodic)


@_keyword_only("C's egw_psi_from_hardness takes (E*, H, K, sigma, beta)")
def psi_from_hardness(*, modulus: float, hardness: float, sigma: float,
                      summit_radius: float, hardness_coeff: float = 0.6) -> float:
    """The paper's plasticity index psi = 4 E*/(3 pi K H) sqrt(sigma/beta).

    Every argument is keyword-only: the C function egw_psi_from_hardness takes another
    order (modulus, hardness, hardness_coeff, sigma, beta), and a call in that order would
    return a wrong psi without an error.

    Parameters
    ----------
    modulus : float
        Effective modulus E* [pressure], > 0.
    hardness : float
        Hardness H of the softer surface [pressure], > 0.
    sigma : float
        Std of the summit heights [length], > 0.
    summit_radius : float
        Mean summit radius beta [length], > 0.
    hardness_coeff : float
        ZMC K, in (0, 1).

    Returns
    -------
    float
        psi (dimensionless).

    Raises
    ------
    InvalidArgumentError
        A value out of range (named by the library).
    TypeError
        A positional argument.
    """
    psi = ctypes.c_double()
    check(lib.egw_psi_from_hardness(float(modulus), float(hardness), float(hardness_coeff),
                                    float(sigma), float(summit_radius), ctypes.byref(psi)))
    return psi.value


#: The one set of defaults of egw-topo and of the Python functions: periodic maps are
#: detrended by their mean and differentiated by FFT; other maps lose their best-fit plane
#: and use central differences.
DEFAULTS = {"detrend": {True: "mean", False: "plane"},
            "derivatives": {True: "fft", False: "difference"}}
#: the summit-identification and spectral estimates are compared at this relative gap
AGREEMENT_TOL = 0.10
#: a curvature wavelength 2 pi sqrt(m2/m4) under this many pixels: 8-neighbour summit
#: identification is limited by the sampling
PIXELS_PER_WAVELENGTH_MIN = 20.0
#: fewer summits than this: their averages carry more than 5 % statistical error
SUMMITS_STATISTICS_MIN = 400
#: the spectral eta or beta changing by more than this when the pixel size doubles: the
#: roughness goes down to the pixel and GW's parameters are those of the sampling. A map
#: resolving its shortest wavelength by >= 16 pixels changes by ~5 %; a self-affine map
#: rough down to the pixel (Hurst 0.8) by a factor 2-4.
RESOLUTION_TOL = 0.25


def default_detrend(periodic: bool) -> str:
    """The default detrending (DEFAULTS).

    Parameters
    ----------
    periodic : bool
        Whether the map is periodic.

    Returns
    -------
    str
        'mean' for a periodic map, 'plane' otherwise.
    """
    return DEFAULTS["detrend"][bool(periodic)]


def default_derivatives(periodic: bool) -> str:
    """The default derivatives (DEFAULTS).

    Parameters
    ----------
    periodic : bool
        Whether the map is periodic.

    Returns
    -------
    str
        'fft' for a periodic map, 'difference' otherwise.
    """
    return DEFAULTS["derivatives"][bool(periodic)]


#: Bound on a map's scales (in its own unit): pixel sizes in [1/MAP_SCALE, MAP_SCALE],
#: heights and the curvature scale max|z|/min(dx, dy)**2 at most MAP_SCALE, so that the
#: pixel area, the moments m2 ~ (z/dx)**2, m4 ~ (z/dx**2)**2 and the summit density stay
#: finite doubles (a pixel size of 1e-300 divided by zero, 1e300 overflowed).
MAP_SCALE = 1e100


def _check_scales(z: np.ndarray, dx: float, dy: float, what: str) -> None:
    if not (1.0 / MAP_SCALE <= min(dx, dy) and max(dx, dy) <= MAP_SCALE):
        raise ValueError(f"pixel_size = ({dx:g}, {dy:g}): must lie in "
                         f"[{1.0 / MAP_SCALE:g}, {MAP_SCALE:g}] (in the unit of the heights;"
                         " beyond, the moments and the summit density leave the doubles)")
    top = float(np.max(np.abs(z)))
    if top > MAP_SCALE or top / min(dx, dy) ** 2 > MAP_SCALE:
        raise ValueError(f"{what}: heights up to {top:g} on pixel_size = ({dx:g}, {dy:g}):"
                         f" the heights and the curvature scale max|z|/min(dx, dy)**2 must "
                         f"be at most {MAP_SCALE:g} (the moments leave the doubles)")


def _check_unit(unit: Optional[str]) -> None:
    if unit is not None and unit not in LENGTH_UNITS:
        raise ValueError(f"unit = {unit!r}: must be one of {sorted(set(LENGTH_UNITS))}")


def _unit_factor(unit: Optional[str]) -> float:
    if unit is None:
        raise ValueError("the height map has no unit: give unit= (the length unit of the "
                         f"heights and pixel sizes, one of {sorted(set(LENGTH_UNITS))})")
    _check_unit(unit)
    return LENGTH_UNITS[unit]


def _is_surface_topography(source: Any) -> bool:
    return hasattr(source, "heights") and hasattr(source, "physical_sizes") and \
        hasattr(source, "nb_grid_pts")


def _from_surface_topography(top: Any, unit: Optional[str],
                             periodic: Optional[bool]) -> HeightMap:
    if getattr(top, "dim", 2) != 2:
        raise ValueError(f"a SurfaceTopography of dimension {top.dim}: egw needs an areal "
                         "(2-D) map")
    if getattr(top, "has_undefined_data", False):
        raise ValueError("the topography has undefined (NaN) pixels: fill them "
                         "(top.interpolate_undefined_data()) or crop them first")
    top_unit = getattr(top, "unit", None)
    if top_unit is not None and unit is not None and top_unit != unit:
        raise ValueError(f"mixed units: the topography is in {top_unit!r}, unit = {unit!r} "
                         "was given: convert the topography (top.to_unit(...)) instead")
    unit = top_unit if top_unit is not None else unit
    if unit is None:
        raise ValueError("the topography has no unit: give unit= (or make it with unit=...)")
    _check_unit(unit)
    nx, ny = top.nb_grid_pts
    sx, sy = top.physical_sizes
    heights = np.asarray(top.heights(), dtype=np.float64).T  # ST: [x, y]; egw: [y, x]
    if periodic is None:
        periodic = bool(getattr(top, "is_periodic", False))
    return _checked_map(heights, (sx / nx, sy / ny), unit, periodic, "the topography")


def _checked_map(heights: np.ndarray, pixel_size, unit: Optional[str], periodic: bool,
                 what: str) -> HeightMap:
    if np.ma.is_masked(heights):
        raise ValueError(f"{what}: a masked array with {np.ma.count_masked(heights)} masked "
                         "pixels: masked pixels are missing data; fill or crop them first "
                         "(summits and moments are undefined next to them)")
    z = np.asarray(heights, dtype=np.float64)
    if z.ndim != 2 or min(z.shape) < 3:
        raise ValueError(f"{what}: a height map must be a 2-D matrix of at least 3 x 3 "
                         f"values (got shape {z.shape})")
    bad = np.count_nonzero(~np.isfinite(z))
    if bad:
        raise ValueError(f"{what}: {bad} NaN or infinite pixels: fill or crop missing "
                         "data first (summits and moments are undefined next to them)")
    if pixel_size is None:
        raise ValueError(f"{what}: give pixel_size (dx or (dx, dy), in the unit of the "
                         "heights)")
    dx, dy = (pixel_size, pixel_size) if np.isscalar(pixel_size) else pixel_size
    if not (dx > 0 and dy > 0 and math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError(f"pixel_size = {pixel_size}: must be finite and > 0")
    _check_scales(z, float(dx), float(dy), what)
    _check_unit(unit)
    return HeightMap(z, float(dx), float(dy), unit, bool(periodic))


def height_map(source: Any, pixel_size: Union[None, float, Tuple[float, float]] = None,
               unit: Optional[str] = None, *, height_unit: Optional[str] = None,
               periodic: Optional[bool] = None) -> HeightMap:
    """A HeightMap from a numpy array, a SurfaceTopography topography, a HeightMap or a
    file, with its units explicit.

    Parameters
    ----------
    source : ndarray (ny, nx), SurfaceTopography topography, HeightMap or path
        A path ending .npy, .csv or .txt is read by :func:`read_height_map`; any other
        file (x3p, datx, opd, gwy, sur, ...) by SurfaceTopography
        (``pip install "./python[topography]"``), which records its units.
    pixel_size : float or (dx, dy)
        For arrays and plain files: in the unit of the heights.
    unit : str
        Length unit of the heights and pixel sizes ('m', 'mm', 'um', 'nm', ...);
        required for arrays and plain files (the map refuses to guess).
    height_unit : str, optional
        The heights' unit when it must be stated apart: refused unless equal to unit
        (heights in nm on pixels in um are a classic silent error).
    periodic : bool, optional
        Whether the map is periodic (default: SurfaceTopography's is_periodic, else
        False).

    Returns
    -------
    HeightMap

    Raises
    ------
    ValueError
        NaN pixels, a missing or unknown unit, mixed units, a bad pixel size or shape.
    ImportError
        An instrument format without SurfaceTopography installed.
    """
    if height_unit is not None and height_unit != unit:
        raise ValueError(f"mixed units: heights in {height_unit!r}, pixel size in "
                         f"{unit!r}: give both in one unit (scale the heights by "
                         f"{_unit_factor(height_unit) / _unit_factor(unit):g})")
    if isinstance(source, HeightMap):
        if unit is not None and source.unit is not None and unit != source.unit:
            raise ValueError(f"mixed units: the map is in {source.unit!r}, unit = {unit!r}")
        return dataclasses.replace(source, unit=source.unit or unit,
                                   periodic=source.periodic if periodic is None
                                   else bool(periodic))
    if _is_surface_topography(source):
        return _from_surface_topography(source, unit, periodic)
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        if os.path.splitext(path)[1].lower() in (".npy", ".csv", ".txt", ".dat", ""):
            if unit is None:
                raise ValueError(f"{path}: a plain height map carries no unit: give unit= "
                                 "(CLI: --unit)")
            hm = read_height_map(path, 1.0 if pixel_size is None else pixel_size, unit,
                                 bool(periodic))
            if pixel_size is None:
                raise ValueError(f"{path}: give pixel_size (CLI: --pixel-size)")
            return hm
        try:
            import SurfaceTopography as st  # noqa: N813 (the package's own name)
        except ImportError:
            raise ImportError(f"{path}: instrument formats are read by SurfaceTopography: "
                              "pip install './python[topography]' (from the egw "
                              "repository)") from None
        reader = st.open_topography(path)
        kwargs = {}
        if pixel_size is not None:
            dx, dy = (pixel_size, pixel_size) if np.isscalar(pixel_size) else pixel_size
            nx, ny = reader.channels[0].nb_grid_pts
            kwargs["physical_sizes"] = (dx * nx, dy * ny)
        if unit is not None and reader.channels[0].unit is None:
            kwargs["unit"] = unit
        return _from_surface_topography(reader.topography(**kwargs), unit, periodic)
    if unit is None:
        raise ValueError("a height array carries no unit: give unit= (the length unit of "
                         "the heights and pixel sizes)")
    return _checked_map(source, pixel_size, unit, bool(periodic), "the height array")


@dataclass
class TopographyReport:
    """Both estimates of a height map's GW statistics, and which to trust.

    Attributes
    ----------
    shape : (ny, nx)
    unit : the map's length unit (the statistics are in it).
    periodic : bool
    detrend, derivatives : the methods used.
    summits : SummitStatistics from 8-neighbour summit identification.
    spectral : SummitStatistics from the spectral moments (McCool/Nayak).
    moments : the Moments.
    disagreement : relative gaps |summits/spectral - 1| of eta, beta, sigma_s.
    trust : 'summits' or 'spectral'; reason : why.
    warnings : every warning (also issued as TopographyWarning).
    resolution : relative change of the spectral eta ('summit_density') and beta
        ('summit_radius') when the pixel size doubles (:func:`resolution_dependence`);
        above RESOLUTION_TOL the parameters depend on the pixel size (a warning says
        what to do).
    """
    shape: Tuple[int, int]
    unit: Optional[str]
    periodic: bool
    detrend: str
    derivatives: str
    summits: SummitStatistics
    spectral: SummitStatistics
    moments: Moments
    disagreement: Dict[str, float]
    trust: str
    reason: str
    warnings: List[str] = field(default_factory=list)
    resolution: Dict[str, float] = field(default_factory=dict)

    @property
    def recommended(self) -> SummitStatistics:
        """The estimate to use (summits or spectral, see reason)."""
        return self.summits if self.trust == "summits" else self.spectral

    def to_dict(self) -> Dict[str, Any]:
        """The report as a JSON-ready dictionary.

        Returns
        -------
        dict
            Plain numbers, strings and lists (numbers in the map's unit).
        """
        def stats(s: SummitStatistics) -> Dict[str, Any]:
            return {"summit_density": s.summit_density, "summit_radius": s.summit_radius,
                    "sigma_summits": s.sigma_summits, "sigma_surface": s.sigma_surface,
                    "y_s": s.mean_summit_height, "n_summits": s.n_summits,
                    "alpha": s.alpha, "warnings": list(s.warnings)}
        return {"shape": list(self.shape), "unit": self.unit, "periodic": self.periodic,
                "detrend": self.detrend, "derivatives": self.derivatives,
                "moments": {"m0": self.moments.m0, "m2": self.moments.m2,
                            "m4": self.moments.m4, "m2_xy": list(self.moments.m2_xy),
                            "m4_xy": list(self.moments.m4_xy), "alpha": self.moments.alpha},
                "summits": stats(self.summits), "spectral": stats(self.spectral),
                "disagreement": self.disagreement, "trust": self.trust,
                "reason": self.reason, "warnings": list(self.warnings),
                "resolution": dict(self.resolution)}


def coarse_grain(surface: HeightMap, factor: int = 2) -> HeightMap:
    """The map with pixels factor times larger: the means of factor x factor blocks (a
    low-pass at the new pixel; a row or column that fills no block is dropped).

    Parameters
    ----------
    surface : HeightMap
        The map.
    factor : int
        Block size, >= 1.

    Returns
    -------
    HeightMap
        Pixel sizes factor * (dx, dy); the same unit and periodicity.

    Raises
    ------
    ValueError
        A factor < 1, or a map with fewer than 3 x 3 blocks.
    """
    factor = int(factor)
    ny, nx = surface.heights.shape
    if factor < 1 or ny // factor < 3 or nx // factor < 3:
        raise ValueError(f"factor = {factor}: must be >= 1 and leave at least 3 x 3 pixels "
                         f"of the {ny} x {nx} map")
    z = surface.heights[:ny - ny % factor, :nx - nx % factor]
    z = z.reshape(ny // factor, factor, nx // factor, factor).mean(axis=(1, 3))
    return HeightMap(z, surface.dx * factor, surface.dy * factor, surface.unit,
                     surface.periodic and ny % factor == 0 and nx % factor == 0)


def resolution_dependence(surface: HeightMap, derivatives: Optional[str] = None
                          ) -> Dict[str, float]:
    """How much the spectral GW parameters depend on the pixel size: their relative change
    when the map is coarse-grained by 2 (:func:`coarse_grain`).

    On a map whose roughness continues down to the pixel (no short-wavelength cut-off in
    the data), m2 and m4 grow as the pixel shrinks, and so do the summit density and the
    summit curvature: GW's eta and beta are then those of the instrument's sampling, not
    of the surface.

    Parameters
    ----------
    surface : HeightMap
        The detrended map.
    derivatives : {'fft', 'difference'}, optional
        As :func:`spectral_moments` (default: DEFAULTS).

    Returns
    -------
    dict
        'summit_density' and 'summit_radius': coarse/fine - 1 of the spectral eta and
        beta (|value| > RESOLUTION_TOL: resolution-dependent parameters).

    Raises
    ------
    ValueError
        A map too small to coarse-grain, or vanishing moments.
    """
    derivatives = derivatives or default_derivatives(surface.periodic)
    fine = mccool(spectral_moments(surface, derivatives))
    coarse_map = detrend(coarse_grain(surface, 2), "mean")
    coarse = mccool(spectral_moments(coarse_map, derivatives))
    return {"summit_density": coarse.summit_density / fine.summit_density - 1.0,
            "summit_radius": coarse.summit_radius / fine.summit_radius - 1.0}


def _resolution_note(change: Dict[str, float]) -> Optional[str]:
    worst = max(abs(v) for v in change.values())
    if worst <= RESOLUTION_TOL:
        return None
    return (f"resolution: doubling the pixel size changes the spectral summit density by "
            f"{100 * change['summit_density']:+.0f} % and the summit radius by "
            f"{100 * change['summit_radius']:+.0f} %: the roughness goes down to the pixel, "
            "so eta and beta (and mu, psi) are those of the sampling, not of the surface. "
            "Cut the map off at a physical short-wavelength limit (the smallest wavelength "
            "that carries load: coarse_grain or a low-pass filter) and check the result no "
            "longer changes, or use a contact law that needs no summit statistics (Persson's "
            "theory, a BEM rough-flat law)")


def _trust(hm: HeightMap, summits: SummitStatistics, moments: Moments) -> Tuple[str, str]:
    """Which estimate to trust, and why: McCool's formulas need alpha >> 1 and an
    isotropic surface; 8-neighbour identification needs the curvature wavelength
    2 pi sqrt(m2/m4) well sampled and enough summits for its averages."""
    alpha = moments.alpha
    wavelength = 2 * math.pi * math.sqrt(moments.m2 / moments.m4) / math.sqrt(hm.dx * hm.dy)
    n = summits.n_summits or 0
    (m2x, m2y) = moments.m2_xy
    if alpha < ALPHA_WARN:
        return "summits", (f"bandwidth: alpha = {alpha:.3g} < {ALPHA_WARN}, and McCool's "
                           "formulas assume alpha >> 1; the summits found on the map are the "
                           "direct estimate")
    if wavelength < PIXELS_PER_WAVELENGTH_MIN:
        return "spectral", (f"sampling: the curvature wavelength 2 pi sqrt(m2/m4) spans "
                            f"{wavelength:.3g} pixels (< {PIXELS_PER_WAVELENGTH_MIN:g}), so "
                            "8-neighbour identification merges and misses summits; the "
                            "moments count every resolved wavelength (both depend on the "
                            "pixel size: sample finer if you can)")
    if n < SUMMITS_STATISTICS_MIN:
        return "spectral", (f"statistics: {n} summits carry a {100 / math.sqrt(max(n, 1)):.0f}"
                            " % error; the moments average over every pixel")
    if max(m2x, m2y) > 1.5 * min(m2x, m2y):
        return "summits", ("anisotropy: McCool's formulas assume an isotropic surface; the "
                           "summits found are the direct estimate")
    return "summits", (f"the summits are resolved ({wavelength:.3g} pixels per curvature "
                       f"wavelength, {n} summits, alpha = {alpha:.3g}) and their direct "
                       "statistics need no Gaussian isotropic surface")


def analyse(source: Any, pixel_size=None, unit: Optional[str] = None, *,
            periodic: Optional[bool] = None, detrend_mode: Optional[str] = None,
            derivatives: Optional[str] = None) -> TopographyReport:
    """GW statistics of a height map both ways, compared (the analysis of egw-topo).

    Parameters
    ----------
    source, pixel_size, unit, periodic
        As :func:`height_map`.
    detrend_mode : {'mean', 'plane'}, optional
        Default: 'mean' for periodic maps, 'plane' otherwise (DEFAULTS).
    derivatives : {'fft', 'difference'}, optional
        Default: 'fft' for periodic maps, 'difference' otherwise (DEFAULTS).

    Returns
    -------
    TopographyReport
        Numbers in the map's unit. When the two estimates of eta, beta or sigma_s differ
        by more than 10 % a TopographyWarning says which to trust and why.

    Raises
    ------
    ValueError
        As :func:`height_map`, or a map with fewer than 2 summits.
    """
    hm = height_map(source, pixel_size, unit, periodic=periodic)
    detrend_mode = detrend_mode or default_detrend(hm.periodic)
    derivatives = derivatives or default_derivatives(hm.periodic)
    hm = detrend(hm, detrend_mode)
    moments = spectral_moments(hm, derivatives)
    spectral = mccool(moments)
    summits = summit_statistics(hm, hm.periodic)
    gaps = {"summit_density": summits.summit_density / spectral.summit_density - 1.0,
            "summit_radius": summits.summit_radius / spectral.summit_radius - 1.0,
            "sigma_summits": summits.sigma_summits / spectral.sigma_summits - 1.0}
    trust, reason = _trust(hm, summits, moments)
    notes = list(summits.warnings) + list(spectral.warnings)
    worst = max(gaps, key=lambda k: abs(gaps[k]))
    if abs(gaps[worst]) > AGREEMENT_TOL:
        notes.append(f"summit identification and spectral estimates disagree: {worst} "
                     f"differs by {100 * gaps[worst]:+.0f} % (> {100 * AGREEMENT_TOL:.0f} %); "
                     f"trust the {trust} estimate: {reason}")
    (m2x, m2y), (m4x, m4y) = moments.m2_xy, moments.m4_xy
    if max(m2x, m2y) > 1.5 * min(m2x, m2y):
        notes.append(f"anisotropic: m2 along x and y differ ({m2x:.3g}, {m2y:.3g}); GW's "
                     "isotropic formulas use their mean")
    resolution = resolution_dependence(hm, derivatives) if min(hm.heights.shape) >= 12 \
        else {}
    note = _resolution_note(resolution) if resolution else None
    if note:
        notes.append(note)
    for note in notes:
        warnings.warn(note, TopographyWarning, stacklevel=2)
    return TopographyReport(hm.heights.shape, hm.unit, hm.periodic, detrend_mode,
                            derivatives, summits, spectral, moments,
                            {k: float(abs(v)) for k, v in gaps.items()}, trust, reason,
                            notes, resolution)


#: models whose overlap delta is measured from the mean SUMMIT plane (GW's base plane);
#: a model measured from the mean plane of the heights (y_s = 0) is simply not listed here
SUMMIT_PLANE_MODELS = ("GW", "E-GW", "EP-GW")


def reference_plane_offset(model: str, stats: SummitStatistics) -> float:
    """The height y_s of a model's reference plane above the mean plane of the heights.

    An overlap delta_m measured from the mean plane of the heights is delta = delta_m + y_s
    for the model; a separation u between the mean planes is d = u - y_s.

    Parameters
    ----------
    model : str
        The model name ('GW', 'E-GW', 'EP-GW', ...).
    stats : SummitStatistics
        The statistics of the surface (their mean_summit_height is used).

    Returns
    -------
    float
        y_s [the unit of stats]: the mean summit height (> 0) for the models in
        SUMMIT_PLANE_MODELS, whose delta is measured from the mean summit plane; 0 for a
        model measured from the mean plane of the heights.

    Raises
    ------
    ValueError
        A summit-plane model whose statistics carry no mean summit height.
    """
    if model not in SUMMIT_PLANE_MODELS:
        return 0.0
    if stats.mean_summit_height is None:
        raise ValueError(f"model {model!r} measures delta from the mean summit plane, but "
                         f"the statistics ({stats.method}) carry no mean summit height")
    return float(stats.mean_summit_height)


@dataclass
class ContactReport:
    """How contact_from_topography got its Params.

    Attributes
    ----------
    params : the Params returned.
    estimate : 'summits' or 'spectral', the statistics used; reason : why.
    summit_density, summit_radius, sigma, sigma_surface : the combined surface's
        statistics [SI: 1/m^2, m].
    y_s : the offset of the model's reference plane above the mean plane of the heights
        [m]: an overlap delta_m measured from the mean plane is delta = delta_m + y_s for
        the model (a separation u between mean planes: d = u - y_s). GW, E-GW and EP-GW
        measure from the mean summit plane, which lies the mean summit height above the
        mean plane (y_s > 0); a model measured from the mean plane has y_s = 0
        (:func:`reference_plane_offset`).
    effective_modulus : E* [Pa]; radius : R [m] (None for a flat).
    surfaces : the TopographyReport of each map analysed (empty for moments).
    notes : warnings and assumptions.
    """
    params: Params
    estimate: str
    reason: str
    summit_density: float
    summit_radius: float
    sigma: float
    y_s: float
    sigma_surface: float
    effective_modulus: float
    radius: Optional[float]
    surfaces: List[TopographyReport] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)


def contact_from_topography(top1: Any, top2: Any = None, *, radius: Optional[float],
                            E1: float, nu1: float, E2: Optional[float] = None,
                            nu2: Optional[float] = None, model: str = "E-GW",
                            hardness: Optional[float] = None, hardness_coeff: float = 0.6,
                            pixel_size=None, unit: Optional[str] = None,
                            estimate: str = "auto") -> Tuple[Params, ContactReport]:
    """From one or two measured surfaces to the Params of their contact, in one call.

    Parameters
    ----------
    top1, top2 : height map source or Moments
        Anything :func:`height_map` takes (numpy array with pixel_size and unit,
        SurfaceTopography topography, HeightMap, file), or the profile Moments of a
        surface in metres. top2 None: a smooth counter-face. Two maps: their sum surface
        (same grid); two Moments: their sum (independent surfaces).
    radius : float or None
        Equivalent radius R = R1 R2/(R1 + R2) [m]; None for a flat (mu is then computed
        for R = 1 m: flat_pressure depends on mu/sqrt(R) only, so R cancels).
    E1, nu1, E2, nu2 : float
        Young's moduli [Pa] and Poisson's ratios (E2, nu2 default to body 1's).
    model : {'GW', 'E-GW', 'EP-GW', 'Persson', 'BEM'}
        GW's summit models, or a rough-flat law of the combined surface
        (doc/theory.md section 11): 'Persson' from its radially averaged power spectrum,
        'BEM' from egw's periodic boundary-element solver on the map itself (a periodic
        map; a non-periodic one is refused). The last two return Params with a
        ``flat_law`` (model "flat law"), delta measured from the mean plane (y_s = 0).
    hardness : float, optional
        Hardness of the softer body [Pa]; needed for EP-GW (psi from it).
    hardness_coeff : float
        ZMC K.
    pixel_size, unit :
        For numpy arrays and plain files (as :func:`height_map`).
    estimate : {'auto', 'summits', 'spectral'}
        Which statistics of a map to use: 'auto' follows the report's advice.

    Returns
    -------
    params : Params
        model, R (1 for a flat), E*, sigma (summit heights of the combined surface), mu,
        psi (EP-GW), in SI units.
    report : ContactReport
        The statistics used (with y_s) and the estimates of each map.

    Raises
    ------
    ValueError
        Missing units, NaN pixels, maps on different grids, EP-GW without hardness.
    """
    if model not in ("GW", "E-GW", "EP-GW", "Persson", "BEM"):
        raise ValueError(f"model = {model!r}: a rough contact needs 'GW', 'E-GW', 'EP-GW', "
                         "'Persson' or 'BEM'")
    if model in ("Persson", "BEM") and isinstance(top1, Moments):
        raise ValueError(f"model {model!r} needs a height map (a power spectrum or the map "
                         "itself), not profile Moments")
    if model == "EP-GW" and hardness is None:
        raise ValueError("model EP-GW needs hardness= (psi follows from it)")
    if estimate not in ("auto", "summits", "spectral"):
        raise ValueError(f"estimate = {estimate!r}: 'auto', 'summits' or 'spectral'")
    notes: List[str] = []
    surfaces: List[TopographyReport] = []
    if isinstance(top1, Moments):
        if top2 is not None and not isinstance(top2, Moments):
            raise ValueError("give two Moments or two maps, not one of each")
        moments = top1 if top2 is None else top1 + top2
        stats = mccool(moments)
        chosen, reason = "spectral", "profile moments given: McCool's formulas"
        notes += stats.warnings
    else:
        maps = [height_map(t, pixel_size, unit).to_metres() for t in (top1, top2)
                if t is not None]
        surface = maps[0] if len(maps) == 1 else sum_surface(*maps)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            rep = analyse(surface)
        if model in SUMMIT_PLANE_MODELS:   # (a flat law uses no summit statistics)
            for w in caught:
                warnings.warn(w.message, w.category, stacklevel=2)
        surfaces.append(rep)
        chosen = rep.trust if estimate == "auto" else estimate
        reason = rep.reason if estimate == "auto" else "asked for"
        stats = rep.summits if chosen == "summits" else rep.spectral
        notes += rep.warnings
    e_star = effective_modulus(E1, nu1, E2, nu2)
    r_mu = 1.0 if radius is None else float(radius)
    if radius is None:
        notes.append("radius None: a flat; mu computed for R = 1 m (flat_pressure depends "
                     "on mu/sqrt(R) only)")
    mu = mu_from_summits(summit_density=stats.summit_density,
                         summit_radius=stats.summit_radius, sigma=stats.sigma_summits,
                         radius=r_mu)
    psi = 0.0
    if model == "EP-GW":
        psi = psi_from_hardness(modulus=e_star, hardness=hardness, sigma=stats.sigma_summits,
                                summit_radius=stats.summit_radius,
                                hardness_coeff=hardness_coeff)
    if model in ("Persson", "BEM"):
        from .flat_law import FlatLaw
        law = FlatLaw.from_topography(surface, e_star, model)
        params = Params(radius=r_mu, modulus=e_star, flat_law=law)
        notes.append(f"model {model}: a rough-flat law of the surface (length "
                     f"{law.length:.6g} m, its rms height); delta from the mean plane")
    else:
        params = Params(model=model, radius=r_mu, modulus=e_star,
                        sigma=stats.sigma_summits, mu=mu, psi=psi,
                        hardness_coeff=hardness_coeff)
    report = ContactReport(params, chosen, reason, stats.summit_density, stats.summit_radius,
                           stats.sigma_summits, reference_plane_offset(model, stats),
                           stats.sigma_surface, e_star, radius, surfaces, notes)
    return params, report


def _write_flat_law(surface: HeightMap, args) -> List[str]:
    """egw-topo --model: the surface's law (and the sphere's table) written, as lines."""
    from .flat_law import FlatLaw
    from .tables import Table
    if args.modulus is None:
        raise ValueError("--model needs --modulus (E* in Pa)")
    law = FlatLaw.from_topography(surface, args.modulus, args.model)
    law.write(args.law)
    lines = [f"{args.model} rough-flat law: length {law.length:.6g} m, u in "
             f"[{law.separation_range[0]:.6g}, {law.separation_range[1]:.6g}] m: "
             f"wrote {args.law}"]
    if args.radius is not None:
        r = args.radius * _unit_factor(surface.unit)
        t = Table.build(Params(radius=r, modulus=args.modulus, flat_law=law),
                        -3 * law.length, 10 * law.length, 1e-4)
        t.write(args.table, "csv")
        lines.append(f"sphere R = {r:.6g} m on the law: 1-D table, overlaps from the mean "
                     f"plane [-3, 10] x {law.length:.6g} m: wrote {args.table}")
    return lines


def _choose_lines(surface: HeightMap, args) -> List[str]:
    """egw-topo --choose: every model against the surface's BEM law, as lines."""
    from .surface_choice import choose_for_surface
    if args.radius is None or args.modulus is None:
        raise ValueError("--choose needs --radius and --modulus (E* in Pa)")
    try:
        lo, hi = (float(v) for v in args.overlaps.split(","))
    except ValueError:
        raise ValueError(f"--overlaps {args.overlaps!r}: MIN,MAX (numbers)") from None
    r = args.radius * _unit_factor(surface.unit)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the summit advice is printed above already
        c = choose_for_surface(surface, radius=r, modulus=args.modulus, tol=args.choose,
                               delta_min_sigma=lo, delta_max_sigma=hi)
    lines = [f"model choice against the surface's BEM law (R = {r:.6g} m, E* = "
             f"{args.modulus:g} Pa, delta_m in [{lo:g}, {hi:g}] rms heights, error "
             f"{'relative to the largest force' if c.relative_to_max else 'pointwise'}):"]
    for m in c.candidates[:-1]:
        lines.append(f"  {m.model:8s} error {m.error:.3g}  (y_s {m.y_s:.4g} m, set-up "
                     f"{m.seconds:.3g} s)")
    lines.append(f"  choice: {c.reason}")
    return lines


def _report(stats: SummitStatistics, radius, modulus, hardness, k, unit) -> List[str]:
    u = f" {unit}" if unit else ""
    lines = [f"{stats.method}:",
             f"  summit density eta     {stats.summit_density:.6g} per{u}^2",
             f"  summit radius beta     {stats.summit_radius:.6g}{u}",
             f"  summit height std      {stats.sigma_summits:.6g}{u}",
             f"  surface rms height     {stats.sigma_surface:.6g}{u}",
             f"  y_s (mean summit plane above the mean plane)  "
             f"{stats.mean_summit_height:.6g}{u}"]
    if stats.n_summits is not None:
        lines.append(f"  summits found          {stats.n_summits}")
    if stats.alpha is not None:
        lines.append(f"  bandwidth alpha        {stats.alpha:.6g}")
    if radius is not None:
        mu = mu_from_summits(summit_density=stats.summit_density,
                             summit_radius=stats.summit_radius, sigma=stats.sigma_summits,
                             radius=radius)
        lines.append(f"  mu (R = {radius:g})        {mu:.6g}")
    if modulus is not None and hardness is not None:
        psi = psi_from_hardness(modulus=modulus, hardness=hardness, sigma=stats.sigma_summits,
                                summit_radius=stats.summit_radius, hardness_coeff=k)
        lines.append(f"  psi (E* = {modulus:g}, H = {hardness:g}, K = {k:g})  {psi:.6g}")
    return lines


def _pixel_size(text: str) -> Tuple[float, float]:
    parts = text.replace(",", " ").split()
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: dx or dx,dy (numbers)") from None
    if len(values) not in (1, 2):
        raise argparse.ArgumentTypeError(f"{text!r}: dx or dx,dy")
    return (values[0], values[-1])


def main(argv: Optional[Sequence[str]] = None) -> int:
    """egw-topo: GW parameters of one height map, or of the sum surface of two.

    Parameters
    ----------
    argv : sequence of str, optional
        The command line without the program name (default: sys.argv[1:]).

    Returns
    -------
    int
        The exit status: 0, or 2 after a message on stderr (bad map, unit, file).

    Raises
    ------
    SystemExit
        From argparse, for bad options or --help.
    """
    ap = argparse.ArgumentParser(
        prog="egw-topo", description="Greenwood-Williamson parameters (sigma, eta, beta, "
        "y_s) of a measured height map, by summit identification and by spectral moments, "
        "with which to trust. Options may come in any order.")
    ap.add_argument("maps", nargs="+", help="height map(s): .npy, .csv or a text matrix "
                    "(with --pixel-size and --unit), or an instrument file SurfaceTopography "
                    "reads (x3p, datx, opd, gwy, ...); two maps: their sum surface")
    ap.add_argument("--pixel-size", type=_pixel_size, metavar="D",
                    help="pixel size dx or dx,dy in the unit of the heights")
    ap.add_argument("--unit", help="length unit of the heights and pixel size (m, mm, um, "
                    "nm, ...); required for plain maps")
    ap.add_argument("--radius", type=float, help="equivalent sphere radius R (in --unit): "
                    "print mu")
    ap.add_argument("--modulus", type=float, help="effective modulus E*: with --hardness, psi")
    ap.add_argument("--hardness", type=float, help="hardness H (units of --modulus)")
    ap.add_argument("--K", type=float, default=0.6, help="ZMC hardness coefficient (0.6)")
    ap.add_argument("--derivatives", choices=["difference", "fft"], default=None,
                    help="derivatives for the moments (default: fft for periodic maps, "
                    "central differences otherwise)")
    ap.add_argument("--detrend", choices=["mean", "plane"], default=None,
                    help="default: mean for periodic maps, plane otherwise")
    ap.add_argument("--periodic", action="store_true", default=None,
                    help="the map is periodic")
    ap.add_argument("--json", metavar="PATH", help="also write the report as JSON to PATH "
                    "('-': standard output, instead of the text)")
    ap.add_argument("--model", choices=["BEM", "Persson"], default=None,
                    help="also compute the surface's rough-flat law (needs --modulus in Pa; "
                    "BEM needs a periodic map) and write it to --law; with --radius also "
                    "the sphere's force table to --table (lengths in m, forces in N)")
    ap.add_argument("--law", metavar="PATH", default="flat_law.csv",
                    help="where --model writes the law (default flat_law.csv)")
    ap.add_argument("--table", metavar="PATH", default="flat_law_table.csv",
                    help="where --model with --radius writes the sphere's 1-D table "
                    "(egw CSV, overlaps -3 to 10 law lengths, tol 1e-4; default "
                    "flat_law_table.csv)")
    ap.add_argument("--choose", metavar="TOL", type=float, default=None,
                    help="also choose the cheapest model (Hertz, GW, E-GW, Persson, the BEM "
                    "law) whose sphere force stays within TOL of the sphere with the "
                    "surface's BEM law (needs --radius, --modulus in Pa, a periodic map)")
    ap.add_argument("--overlaps", metavar="MIN,MAX", default="0.5,10",
                    help="--choose's overlap range with the mean plane, in rms heights "
                    "(default 0.5,10)")
    args = ap.parse_args(argv)
    try:
        if len(args.maps) > 2:
            raise ValueError("give one height map, or two for their sum surface")
        maps = [height_map(m, args.pixel_size, args.unit, periodic=args.periodic)
                for m in args.maps]
        surface = maps[0] if len(maps) == 1 else sum_surface(*maps)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            rep = analyse(surface, detrend_mode=args.detrend, derivatives=args.derivatives)
        lines = [f"egw-topo: {' + '.join(args.maps)}, {rep.shape[1]} x {rep.shape[0]} "
                 f"pixels, unit {rep.unit}, {'periodic' if rep.periodic else 'not periodic'}"
                 f" (detrend {rep.detrend}, derivatives {rep.derivatives})"]
        for stats in (rep.summits, rep.spectral):
            lines += _report(stats, args.radius, args.modulus, args.hardness, args.K,
                             rep.unit)
        lines.append(f"trust: {rep.trust} ({rep.reason})")
        lines += [f"WARNING: {w.message}" for w in caught]
        if args.model is not None:
            lines += _write_flat_law(surface, args)
        if args.choose is not None:
            lines += _choose_lines(surface, args)
        data = rep.to_dict()
        if args.json == "-":
            print(json.dumps(data, indent=2))
        else:
            print("\n".join(lines))
            if args.json:
                tmp = args.json + ".tmp"
                with open(tmp, "w") as f:
                    json.dump(data, f, indent=2)
                os.replace(tmp, args.json)
    except (ValueError, OSError, ImportError) as exc:
        print(f"egw-topo: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
