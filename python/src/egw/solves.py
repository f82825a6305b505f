"""Rough-sphere solves on loading and unloading, and the pressure and deflection
profile of one solve, vectorised over numpy arrays.

Units: any consistent set (SI: m, Pa, N). delta is the overlap of the undeformed
sphere with the mean summit plane, > 0 overlap, < 0 separation; forces and
pressures are positive in compression.
"""
from __future__ import annotations

import ctypes
import warnings
from dataclasses import dataclass
from typing import Optional, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _capi
from ._capi import lib
from .errors import (OK, PointFailedWarning, _FAILED, _exception, _point_index, _require, check,
                     last_error)
from .params import (ArrayLike, FloatOrArray, Options, Params, RESULT_DTYPE, _number_array,
                     _c_scalar, _options, _params)
from ._calls import _Batch, _array, _double_ptr

@dataclass
class SolveResult:
    """Results of solves (floats for one point, arrays of the broadcast shape otherwise).

    Attributes
    ----------
    force : total force P [force], >= 0 (compression positive).
    stiffness : dP/ddelta [force/length].
    contact_radius : effective contact radius a* [length] (Hertz or sigma = 0 with the
        flow-pressure cap beyond first yield: the contact's edge a, not a*).
    max_pressure : largest pressure of the profile [pressure].
    est_rel_err : estimated error of the force relative to |force| (1 for force 0).
        Unloading after a capped loading is accepted against rel_tol/2 of
        max(|force|, 1e-6 force(delta_max)), so below that floor it may exceed rel_tol.
    iterations : nonlinear iterations of the final solve (-1 for a failed point under
        ``errstate(failed="nan")``).
    """
    force: FloatOrArray
    stiffness: FloatOrArray
    contact_radius: FloatOrArray
    max_pressure: FloatOrArray
    est_rel_err: FloatOrArray
    iterations: Union[int, NDArray[np.int32]]


_RESULT_FIELDS = ("force", "stiffness", "contact_radius", "max_pressure", "est_rel_err")


def _solve_result(b: "_Batch", res: np.ndarray) -> SolveResult:
    if b.shape == ():
        return SolveResult(**{f: float(res[f][0]) for f in _RESULT_FIELDS},
                           iterations=int(res["iterations"][0]))
    return SolveResult(**{f: np.ascontiguousarray(res[f]).reshape(b.shape)
                          for f in _RESULT_FIELDS},
                       iterations=np.ascontiguousarray(res["iterations"]).reshape(b.shape))


def _solve(params, delta, delta_max, options) -> SolveResult:
    inputs = {"delta": delta} if delta_max is None else {"delta": delta,
                                                          "delta_max": delta_max}
    b = _Batch(params, **inputs)
    res = np.empty(b.n, dtype=RESULT_DTYPE)
    o = _options(options)
    pd, sd = b.inputs["delta"]
    pm, sm = b.inputs.get("delta_max", (None, 0))
    b.run(lambda flags, nf: lib.egw_solve_array(
        b.params[0], b.params[1], o, b.n, pd, sd, pm, sm,
        res.ctypes.data_as(ctypes.POINTER(_capi.Result)), flags, nf))
    return _solve_result(b, res)


def _single(params, delta, delta_max, options) -> Optional[SolveResult]:
    """One point: the scalar C call, whose solve threads its assembly (None otherwise)."""
    if not (isinstance(params, Params) and params.is_scalar):
        return None
    d = _number_array("delta", delta)
    dm = None if delta_max is None else _number_array("delta_max", delta_max)
    if d.ndim or (dm is not None and dm.ndim):
        return None
    res = _capi.Result()
    p, o = params.to_c(), _options(options)
    if dm is None:
        status = lib.egw_solve(ctypes.byref(p), o, float(d), ctypes.byref(res))
    else:
        status = lib.egw_solve_unload(ctypes.byref(p), o, float(d), float(dm),
                                      ctypes.byref(res))
    if status != OK and _FAILED.get() != "raise":
        if _FAILED.get() == "warn":
            warnings.warn("1 of 1 points failed and is NaN", PointFailedWarning, stacklevel=3)
        nan = float("nan")
        return SolveResult(nan, nan, nan, nan, nan, -1)
    check(status)
    return SolveResult(res.force, res.stiffness, res.contact_radius, res.max_pressure,
                       res.est_rel_err, res.iterations)


def solve(params: Params, delta: ArrayLike, options: Optional[Options] = None) -> SolveResult:
    """Full rough-sphere solve (axisymmetric elastic half-space with the model's summit
    layer) at each overlap.

    Parameters
    ----------
    params : Params
        Any model; array fields broadcast with delta (many contacts in one call).
    delta : float or array
        Overlap of the undeformed sphere with the mean summit plane [length]: > 0 pressed
        together, < 0 apart (rough models carry force there).
    options : Options, optional
        Tolerance and threads. An array runs its points over ``options.n_threads`` OpenMP
        threads (0: the OpenMP default), each solve single-threaded; one point threads
        its own assembly. Results do not depend on the thread count.

    Returns
    -------
    SolveResult
        Floats for scalar inputs, arrays of the broadcast shape otherwise.

    Raises
    ------
    TypeError
        delta is None, a string or not real (e.g. ``solve(p, None)``).
    InvalidArgumentError
        A NaN overlap or bad options (the message names the index).
    NotConvergedError
        A solve did not reach its tolerance.
    """
    if isinstance(params, Params) and params.flat_law is not None:
        return _solve_flat_law(params, delta, options)
    single = _single(params, delta, None, options)
    return single if single is not None else _solve(params, delta, None, options)


def _solve_flat_law(params: Params, delta: ArrayLike, options: Optional[Options]
                    ) -> SolveResult:
    """solve() with a rough-flat law: egw_solve_flat_law at each overlap (scalar params)."""
    if not params.is_scalar:
        raise TypeError("Params with a flat_law takes scalar radius and modulus")
    d = np.asarray(_number_array("delta", delta), dtype=np.float64)
    p, o = params.to_c(), _options(options)
    law = params.flat_law._ptr
    out = np.full((5,) + d.shape, np.nan)
    iters = np.full(d.shape, -1, dtype=np.int64)
    # flat views (out[k] of a scalar delta is a numpy scalar, not a view: writing through
    # out[k].reshape(-1) lost every result and a scalar solve came back NaN)
    out_flat, iters_flat = out.reshape(5, -1), iters.reshape(-1)
    res = _capi.Result()
    failed = 0
    for i, x in enumerate(d.reshape(-1)):
        status = lib.egw_solve_flat_law(ctypes.byref(p), law, o, float(x), ctypes.byref(res))
        if status != OK:
            if _FAILED.get() == "raise":
                message = last_error()
                raise _exception(status, message if d.ndim == 0 else
                                 f"index {_point_index(i, d.shape)}: {message}")
            failed += 1
            continue
        for k, v in enumerate((res.force, res.stiffness, res.contact_radius, res.max_pressure,
                               res.est_rel_err)):
            out_flat[k, i] = v
        iters_flat[i] = res.iterations
    if failed and _FAILED.get() == "warn":
        warnings.warn(f"{failed} of {d.size} points failed and are NaN", PointFailedWarning,
                      stacklevel=3)
    if d.ndim == 0:
        return SolveResult(*(float(out[k]) for k in range(5)), int(iters))
    return SolveResult(*(out[k] for k in range(5)), iters)


def solve_unload(params: Params, delta: ArrayLike, delta_max: ArrayLike,
                 options: Optional[Options] = None) -> SolveResult:
    """EP-GW unloading/reloading solve at delta after loading to delta_max.

    Parameters
    ----------
    params : Params
    delta, delta_max : float or array
        Overlap and the deepest overlap reached before [length], broadcast;
        delta >= delta_max is the loading solve.
    options : Options, optional
        As :func:`solve`.

    Returns
    -------
    SolveResult

    Raises
    ------
    InvalidArgumentError, NotConvergedError
        As :func:`solve`.
    """
    _require("egw_solve_unload")
    single = _single(params, delta, delta_max, options)
    return single if single is not None else _solve(params, delta, delta_max, options)


def profile(params: Params, delta: float, r: ArrayLike,
            options: Optional[Options] = None, *, delta_max: Optional[float] = None
            ) -> Tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Total pressure p(r) and surface deflection w(r) of the solved contact at delta.

    With ``delta_max`` the contact is the unloading (or reloading) one after the largest
    overlap ``delta_max`` (C ``egw_profile_unload``; its force is :func:`solve_unload`'s):
    EP-GW takes the rough unloading law, reversible models (Hertz below first yield, GW,
    E-GW, psi = 0) give the loading profile at delta, and the smooth sphere with the
    flow-pressure cap loaded beyond first yield its elastic contact of the deformed shape
    (a rough sphere with the cap: its total pressure <= p_y).
    ``delta >= delta_max`` is the loading profile. With the cap (smooth sphere, loading or
    unloading) the deflection is the surfaces' total normal displacement, elastic plus the
    plastic crater, so that ``r**2/(2R) - delta + w`` is 0 on the contact; the cap's
    pressures come from its solver's rings (within ~1.5e-5 p_y, whatever rel_tol).

    Parameters
    ----------
    params : Params
        Scalar fields.
    delta : float
        Overlap [length] (sign as in :func:`solve`).
    r : array
        Radii >= 0 [length], any order.

    options : Options, optional
        Solver options.
    delta_max : float, optional
        Largest overlap reached before [length] (keyword only): the unloading profile.

    Returns
    -------
    pressure, deflection : ndarray
        Flat arrays of len(r) [pressure], [length].

    Raises
    ------
    InvalidArgumentError
        Invalid parameters, a NaN overlap or delta_max, or a negative radius.
    TypeError
        delta or delta_max not one real number (an array, a string, a bool).
    NotConvergedError
        The solve did not converge (also the small-sigma route's refusal, whose
        unloading profile is the smooth cap's shifted to the route's force).
    """
    p = _params(params)
    radii = _array(r, "r").reshape(-1).copy()
    pressure = np.empty_like(radii)
    deflection = np.empty_like(radii)
    d = _c_scalar("delta", delta)
    if delta_max is None:
        check(lib.egw_profile(ctypes.byref(p), _options(options), d, radii.size,
                              _double_ptr(radii), _double_ptr(pressure),
                              _double_ptr(deflection)))
    else:
        check(lib.egw_profile_unload(ctypes.byref(p), _options(options), d,
                                     _c_scalar("delta_max", delta_max), radii.size,
                                     _double_ptr(radii), _double_ptr(pressure),
                                     _double_ptr(deflection)))
    return pressure, deflection
