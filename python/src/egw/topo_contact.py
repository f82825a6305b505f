"""From one or two measured surfaces to a contact's parameters: psi from the hardness,
the summit plane's offset and contact_from_topography."""
from __future__ import annotations

import ctypes
import warnings
from dataclasses import dataclass, field
from typing import Any, List, Optional, Tuple

from ._capi import lib
from .errors import _brief, check
from .params import Params, _c_scalar
from ._calls import _keyword_only
from .functions import effective_modulus, mu_from_summits
from .topo_maps import height_map, sum_surface
from .topo_spectra import Moments
from .topo_summits import SummitStatistics, mccool
from .topo_analysis import TopographyReport, analyse


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
    check(lib.egw_psi_from_hardness(_c_scalar("modulus", modulus),
                                    _c_scalar("hardness", hardness),
                                    _c_scalar("hardness_coeff", hardness_coeff),
                                    _c_scalar("sigma", sigma),
                                    _c_scalar("summit_radius", summit_radius),
                                    ctypes.byref(psi)))
    return psi.value


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
        raise ValueError(f"model {_brief(model)} measures delta from the mean summit plane, but "
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
    TypeError
        radius (or another number) not a real number.
    """
    if model not in ("GW", "E-GW", "EP-GW", "Persson", "BEM"):
        raise ValueError(f"model = {_brief(model)}: a rough contact needs 'GW', 'E-GW', 'EP-GW', "
                         "'Persson' or 'BEM'")
    if model in ("Persson", "BEM") and isinstance(top1, Moments):
        raise ValueError(f"model {_brief(model)} needs a height map (a power spectrum or the map "
                         "itself), not profile Moments")
    if model == "EP-GW" and hardness is None:
        raise ValueError("model EP-GW needs hardness= (psi follows from it)")
    if estimate not in ("auto", "summits", "spectral"):
        raise ValueError(f"estimate = {_brief(estimate)}: 'auto', 'summits' or 'spectral'")
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
    r_mu = 1.0 if radius is None else _c_scalar("radius", radius)
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
