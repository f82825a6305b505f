"""The spectral moments of a height map (Nayak 1971): m0, m2, m4 and the bandwidth alpha,
from FFT or central-difference derivatives."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from .errors import _brief
from .topo_maps import HeightMap, default_derivatives


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
    raise ValueError(f"method = {_brief(method)}: must be 'fft' or 'difference'")


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
