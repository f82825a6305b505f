"""The cheapest model of a measured surface's rough sphere that meets a force tolerance,
judged against the BEM law of that surface (issue 31 item 3; doc/scenes.md, "A measured
surface").

The scene chooser (:func:`egw.choose`) judges Hertz against the scene's own rough model:
it cannot tell whether that model is right. Here the truth is egw's sphere with the
surface's own boundary-element flat law (doc/theory.md section 11; against a full BEM of
the rough sphere it is within 3 % where the roughness' longest wavelength is well below
the contact, doc/validation.md), and every cheaper model is measured against it: Hertz,
GW and E-GW from the surface's summits, Persson's law from its spectrum.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, List, Optional, Sequence

import numpy as np

from .errors import _brief
from .params import Options, Params
from .functions import hertz
from .solves import solve

#: candidate models, cheapest first: Hertz needs nothing; GW and E-GW a table from summit
#: statistics; Persson a law from the spectrum, then a table; the BEM law a BEM of the map
MODELS = ("Hertz", "GW", "E-GW", "Persson", "BEM law")


@dataclass
class ModelError:
    """One candidate model measured against the surface's BEM law.

    Attributes
    ----------
    model : str
        'Hertz', 'GW', 'E-GW', 'Persson' or 'BEM law'.
    params : Params
        Its parameters (GW, E-GW: delta = delta_m + y_s; the others: delta = delta_m).
    y_s : float
        Offset of its reference plane above the mean plane of the heights [m].
    error : float
        The error measure against the truth (see :func:`choose_for_surface`).
    force : ndarray
        Its force at the overlaps delta_m [N].
    seconds : float
        Its set-up time here (statistics or law; not the truth's BEM) [s].
    """
    model: str
    params: Params
    y_s: float
    error: float
    force: np.ndarray
    seconds: float


@dataclass
class SurfaceChoice:
    """What :func:`choose_for_surface` found.

    Attributes
    ----------
    model : str
        The cheapest model (in :data:`MODELS` order) whose error is <= tol.
    params : Params
        Its Params (for :func:`egw.solve`, :meth:`egw.Table.build`).
    y_s : float
        Its reference-plane offset [m]: give it delta = delta_m + y_s.
    tol : float
        The tolerance asked for.
    reason : str
        One line: what was chosen and why.
    overlaps : ndarray
        The overlaps delta_m with the mean plane of the heights the models were compared
        at [m].
    truth_force : ndarray
        The truth's force there [N].
    relative_to_max : bool
        True when the error measure is relative to the truth's largest force (the overlap
        range reaches separation, delta_min <= 0).
    candidates : list of ModelError
        Every model measured, cheapest first.
    """
    model: str
    params: Params
    y_s: float
    tol: float
    reason: str
    overlaps: np.ndarray
    truth_force: np.ndarray
    relative_to_max: bool
    candidates: List[ModelError] = field(default_factory=list)


def _error(force, truth, relative_to_max):
    if relative_to_max:
        return float(np.max(np.abs(force - truth)) / np.max(truth))
    return float(np.max(np.abs(force / truth - 1.0)))


def choose_for_surface(top: Any, *, radius: float, modulus: float, tol: float,
                       delta_min_sigma: float = 0.5, delta_max_sigma: float = 10.0,
                       n_overlaps: int = 24, models: Sequence[str] = MODELS[:-1],
                       truth: Any = None, pixel_size=None, unit: Optional[str] = None,
                       periodic: Optional[bool] = None, options: Optional[Options] = None) -> SurfaceChoice:
    """The cheapest model of the rough sphere on a measured surface whose force stays
    within tol of the sphere with the surface's own BEM flat law.

    Parameters
    ----------
    top : height map source
        A periodic height map (anything :func:`egw.topography.height_map` takes); the
        combined surface of the pair.
    radius : float
        Equivalent sphere radius R [m], > 0.
    modulus : float
        Effective modulus E* [Pa], > 0.
    tol : float
        Force tolerance, in (0, 1).
    delta_min_sigma, delta_max_sigma : float
        Overlap range of the scene, delta_m (with the mean plane of the heights) in units
        of the surface's rms height, delta_min_sigma < delta_max_sigma, delta_max_sigma > 0.
    n_overlaps : int
        Overlaps compared, evenly spaced over the range (>= 2).
    models : sequence of str
        Candidates among 'Hertz', 'GW', 'E-GW', 'Persson' (the BEM law is the fallback).
    truth : FlatLaw, optional
        The surface's BEM law if already built (FlatLaw.from_topography(top, modulus,
        'BEM')); built here otherwise.
    pixel_size, unit, periodic :
        For numpy arrays and plain files (as :func:`egw.topography.height_map`).
    options : Options, optional
        Solver options of the sphere solves (default rel_tol 1e-6).

    Returns
    -------
    SurfaceChoice
        The model, its Params and y_s, every candidate's error. The error measure is the
        scene chooser's (doc/scenes.md): max |P/P_true - 1| over the overlaps when
        delta_min_sigma > 0; max |P - P_true| / max P_true when the range reaches
        separation.

    Raises
    ------
    ValueError
        A bad argument (named), a non-periodic map (the BEM law needs a periodic one).
    egw.EgwError
        A failed BEM or solve (egw's message).
    """
    from .flat_law import FlatLaw
    from .topography import contact_from_topography, height_map
    for name, v in (("radius", radius), ("modulus", modulus)):
        if not (np.isfinite(v) and v > 0):
            raise ValueError(f"{name} = {_brief(v)}: must be finite and > 0")
    if not (np.isfinite(tol) and 0 < tol < 1):
        raise ValueError(f"tol = {_brief(tol)}: must lie in (0, 1)")
    if not (np.isfinite(delta_min_sigma) and np.isfinite(delta_max_sigma)
            and delta_min_sigma < delta_max_sigma and delta_max_sigma > 0):
        raise ValueError(f"delta_min_sigma = {_brief(delta_min_sigma)}, delta_max_sigma = "
                         f"{_brief(delta_max_sigma)}: need delta_min_sigma < delta_max_sigma, "
                         "delta_max_sigma > 0")
    if not (isinstance(n_overlaps, (int, np.integer)) and n_overlaps >= 2):
        raise ValueError(f"n_overlaps = {_brief(n_overlaps)}: must be an integer >= 2")
    bad = [m for m in models if m not in MODELS[:-1]]
    if bad:
        raise ValueError(f"models: {bad[0]!r} is not one of {MODELS[:-1]}")
    surface = height_map(top, pixel_size, unit, periodic=periodic)
    if truth is None:
        truth = FlatLaw.from_topography(surface, modulus, "BEM")
    elif not isinstance(truth, FlatLaw):
        raise ValueError(f"truth: a FlatLaw, not {type(truth).__name__}")
    opts = options if options is not None else Options(rel_tol=1e-6)
    sigma = truth.length
    overlaps = np.linspace(delta_min_sigma, delta_max_sigma, n_overlaps) * sigma
    truth_params = Params(radius=radius, modulus=modulus, flat_law=truth)
    truth_force = np.asarray(solve(truth_params, overlaps, opts).force)
    relative_to_max = delta_min_sigma <= 0
    # Params(E1 = 2 E*, nu1 = 0) for both bodies: E* exactly, for contact_from_topography.
    # The map's summits are analysed once: GW and E-GW share the statistics and y_s (both
    # measure delta from the mean summit plane) and differ only in the model; Persson's
    # law needs the spectrum alone.
    found: List[ModelError] = []
    summit_params: Optional[Params] = None
    summit_y_s, summit_seconds = 0.0, 0.0
    for m in MODELS[:-1]:
        if m not in models:
            continue
        t0 = time.perf_counter()
        if m == "Hertz":
            params, y_s = Params(model="Hertz", radius=radius, modulus=modulus), 0.0
            force = np.asarray(hertz(params, overlaps)[0])
        else:
            if m == "Persson":
                params, y_s = Params(radius=radius, modulus=modulus,
                                     flat_law=FlatLaw.from_topography(surface, modulus,
                                                                      "Persson")), 0.0
            else:
                if summit_params is None:
                    summit_params, rep = contact_from_topography(
                        surface, radius=radius, E1=2 * modulus, nu1=0.0, model=m)
                    summit_y_s = rep.y_s
                    summit_seconds = time.perf_counter() - t0
                    t0 = time.perf_counter()
                params, y_s = summit_params.replace(model=m), summit_y_s
            force = np.asarray(solve(params, overlaps + y_s, opts).force)
        seconds = time.perf_counter() - t0 + (summit_seconds if m in ("GW", "E-GW") else 0)
        found.append(ModelError(m, params, y_s, _error(force, truth_force, relative_to_max),
                                force, seconds))
    found.append(ModelError("BEM law", truth_params, 0.0, 0.0, truth_force, float("nan")))
    best = next(c for c in found if c.error <= tol)
    measure = "of the largest force" if relative_to_max else "pointwise"
    if best.model == "BEM law":
        reason = (f"no cheaper model within {tol:g} ({measure}) of the surface's BEM law "
                  f"over delta_m in [{delta_min_sigma:g}, {delta_max_sigma:g}] sigma; "
                  "closest: " + ", ".join(f"{c.model} {c.error:.3g}" for c in found[:-1]))
    else:
        reason = (f"{best.model}: {best.error:.3g} <= {tol:g} ({measure}) against the "
                  f"surface's BEM law over delta_m in [{delta_min_sigma:g}, "
                  f"{delta_max_sigma:g}] sigma, the cheapest that meets it")
    return SurfaceChoice(best.model, best.params, best.y_s, tol, reason, overlaps,
                         truth_force, relative_to_max, found)


__all__ = ["MODELS", "ModelError", "SurfaceChoice", "choose_for_surface"]
