"""A height map analysed: both summit estimates, their agreement, the dependence on the
pixel size and how far GW's parameters can be trusted (analyse, TopographyReport)."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from .topo_maps import (
    HeightMap, coarse_grain, default_derivatives, default_detrend, detrend, height_map)
from .topo_spectra import Moments, spectral_moments
from .topo_summits import (
    ALPHA_WARN, SummitStatistics, TopographyWarning, mccool, summit_statistics)


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
