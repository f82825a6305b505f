"""Impacts: the coefficient of restitution, a DEM time step and the first-yield
overlap and speed of the flow-pressure cap, vectorised over masses and speeds.
"""
from __future__ import annotations

import ctypes
import math
import warnings
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ._capi import lib
from .errors import OK, PointFailedWarning, _FAILED, _exception, check, last_error
from .params import ArrayLike, FloatOrArray, Options, Params, _brief, _number_array, _options
from ._calls import _Batch, _arr, _array, _keyword_only, _loop, _scalar_or_array

@dataclass
class Restitution:
    """A head-on impact (floats for one impact, arrays of the broadcast shape otherwise).

    Attributes
    ----------
    e : coefficient of restitution, 0 < e <= 1.
    work_load : work of the loading curve up to the deepest overlap (= m* v^2/2) [energy].
    dissipated : W_load - W_unload [energy].
    max_overlap : the deepest overlap delta_m [length] (> 0 pressed together, < 0 still
        apart: slow rough impacts turn in the separated tail).
    """
    e: FloatOrArray
    work_load: FloatOrArray
    dissipated: FloatOrArray
    max_overlap: FloatOrArray = float("nan")


@_keyword_only("restitution(params, mass=..., velocity=...)")
def restitution(params: Params, *, mass: ArrayLike, velocity: ArrayLike,
                options: Optional[Options] = None) -> Restitution:
    """Coefficient of restitution of head-on impacts, e = sqrt(W_unload/W_load).

    Parameters
    ----------
    params : Params
        The contact (array fields broadcast).
    mass : float or array, > 0
        Effective mass m*, 1/m* = 1/m1 + 1/m2 [mass].
    velocity : float or array, > 0
        Approach speed from far apart [length/time].
    options : Options, optional
        Tolerance; arrays run over ``options.n_threads`` threads.

    Returns
    -------
    Restitution
        e, work_load, dissipated and max_overlap; one C call (egw_restitution_array).

    Raises
    ------
    InvalidArgumentError
        mass or velocity not finite and > 0 (named with its index).
    NotConvergedError
        A solve failed.
    """
    b = _Batch(params, mass=mass, velocity=velocity)
    e, w_load, w_diss, delta_m = b.out(4)
    o = _options(options)
    (pm, sm), (pv, sv) = b.inputs["mass"], b.inputs["velocity"]
    b.run(lambda flags, nf: lib.egw_restitution_array(
        b.params[0], b.params[1], o, b.n, pm, sm, pv, sv, *_arr(e, w_load, w_diss, delta_m),
        flags, nf))
    return Restitution(*_scalar_or_array(b.shape, e, w_load, w_diss, delta_m))


@dataclass
class TimeStep:
    """The time scales of an impact (floats, or arrays of the broadcast shape).

    Attributes
    ----------
    duration : time the force spends above 1 % of its peak [time].
    step : largest velocity-Verlet step whose error in e stays below the tolerance [time].
    """
    duration: FloatOrArray
    step: FloatOrArray


@_keyword_only("time_step(params, mass=..., velocity=..., tolerance=...)")
def time_step(params: Params, *, mass: ArrayLike, velocity: ArrayLike,
              tolerance: float = 1e-3, options: Optional[Options] = None) -> TimeStep:
    """The time step of a DEM loop for head-on impacts (egw_time_step).

    Parameters
    ----------
    params : Params
    mass : float or array, > 0
        Effective mass m* [mass].
    velocity : float or array, > 0
        The fastest approach speed of the run [length/time] (slower impacts are softer).
    tolerance : float in (0, 0.1]
        Allowed error of the coefficient of restitution from the time step.
    options : Options, optional

    Returns
    -------
    TimeStep
        duration and step; a table-driven loop adds the table's own error.

    Raises
    ------
    TypeError
        A non-numeric input, or a tolerance that is not one number (one per call).
    InvalidArgumentError
        mass, velocity or tolerance out of range (named).
    """
    b = _Batch(params, mass=mass, velocity=velocity)
    duration, step = b.out(2)
    o = _options(options)
    (pm, sm), (pv, sv) = b.inputs["mass"], b.inputs["velocity"]
    tol_array = _number_array("tolerance", tolerance)
    if tol_array.ndim != 0:   # egw_time_step_array takes one tolerance for the whole call
        raise TypeError(f"tolerance = {_brief(tolerance)}: one value for the call (the "
                        "largest step for each tolerance: one call each)")
    tol = float(tol_array)
    b.run(lambda flags, nf: lib.egw_time_step_array(
        b.params[0], b.params[1], o, b.n, pm, sm, pv, sv, tol, *_arr(duration, step),
        flags, nf))
    return TimeStep(*_scalar_or_array(b.shape, duration, step))


@dataclass
class FirstYield:
    """First yield under the flow-pressure cap (floats, or arrays of mass's shape).

    Attributes
    ----------
    overlap : delta_y = (pi p_y/(2 E*))^2 R, where the smooth sphere's peak pressure
        reaches p_y [length] (inf for flow_pressure 0).
    speed : v_y, the approach speed of a head-on impact whose deepest overlap is delta_y
        [length/time] (inf for flow_pressure 0).
    """
    overlap: FloatOrArray
    speed: FloatOrArray


@_keyword_only("first_yield(params, mass=...)")
def first_yield(params: Params, *, mass: ArrayLike) -> FirstYield:
    """First-yield overlap and impact speed of the flow-pressure cap (egw_first_yield).

    Closed forms of the smooth sphere with the params' R and E*, whatever the model (a rough
    sphere's own first yield is where ``solve(...).max_pressure`` reaches p_y): below v_y an
    impact is elastic, above it the cap dissipates (doc/restitution.md).

    Parameters
    ----------
    params : Params
        The contact, with ``flow_pressure`` p_y >= 0 (array fields broadcast with mass).
    mass : float or array, > 0
        Effective mass m*, 1/m* = 1/m1 + 1/m2 [mass].

    Returns
    -------
    FirstYield
        overlap delta_y and speed v_y (floats, or arrays of the broadcast shape); both inf
        where flow_pressure is 0 (no bulk yield).

    Raises
    ------
    InvalidArgumentError
        params invalid, or mass not finite and > 0 (named, with the point's index for
        arrays; ``egw.errstate(failed="nan")`` gives NaN there instead).
    TypeError
        params not an egw.Params.
    """
    b = _Batch(params, mass=mass)
    (pp, sp), (pm, sm) = b.params, b.inputs["mass"]
    mode, failed = _FAILED.get(), 0

    def call(i, dy, vy):
        nonlocal failed
        status = lib.egw_first_yield(ctypes.byref(pp[i * sp]), pm[i * sm], dy, vy)
        if status == OK:
            return
        if mode == "raise":
            message = last_error()
            if b.shape != ():
                index = tuple(int(j) for j in np.unravel_index(i, b.shape))
                message = f"index {index[0] if len(index) == 1 else index}: {message}"
            raise _exception(status, message)
        failed += 1
        dy._obj.value = vy._obj.value = math.nan

    overlap, speed = _loop(b.shape, 2, call)
    if mode == "warn" and failed:
        warnings.warn(f"{failed} of {b.n} points failed and are NaN", PointFailedWarning,
                      stacklevel=3)
    free = (np.broadcast_to(np.asarray(params.flow_pressure, dtype=np.float64), b.shape) == 0) \
        & ~np.isnan(overlap)
    overlap[free] = np.inf    # the C call's DBL_MAX: never
    speed[free] = np.inf
    return FirstYield(*_scalar_or_array(b.shape, overlap, speed))
