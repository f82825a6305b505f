"""The point functions of egw, vectorised over numpy arrays: summit parameters,
effective modulus, Gaussian asperity integrals, elliptic integrals, Hertz and
the rough flat's pressure on loading and unloading.

Units: any consistent set (SI: m, Pa, N); forces and pressures are positive in
compression.
"""
from __future__ import annotations

import ctypes
from typing import Optional, Tuple

import numpy as np

from ._capi import lib
from .errors import INVALID_ARGUMENT, InvalidArgumentError, _flag, _require, check
from .params import ArrayLike, FloatOrArray, Params, _brief, _number_array
from ._calls import _Batch, _arr, _array, _keyword_only, _loop, _scalar_or_array

@_keyword_only("C's egw_mu_from_summits takes (eta, beta, sigma, R)")
def mu_from_summits(*, summit_density: ArrayLike, summit_radius: ArrayLike, sigma: ArrayLike,
                    radius: ArrayLike) -> FloatOrArray:
    """Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta), elementwise with broadcasting.

    Every argument is keyword-only (four lengths and densities a positional call could
    swap without an error).

    Parameters
    ----------
    summit_density : float or array, >= 0
        eta, summits per unit area [1/length^2].
    summit_radius : float or array, >= 0
        beta, mean radius of curvature of the summits [length].
    sigma : float or array, >= 0
        Standard deviation of the summit heights [length].
    radius : float or array, >= 0
        Equivalent radius R of the spheres [length].

    Returns
    -------
    float or ndarray
        mu (dimensionless), of the broadcast shape (a float for scalar inputs).

    Raises
    ------
    InvalidArgumentError
        A negative or non-finite input (named), or an overflowing mu.
    TypeError
        A positional argument, a non-numeric or masked input.
    """
    b = _Batch(None, summit_density=summit_density, summit_radius=summit_radius,
               sigma=sigma, radius=radius)
    flat = [np.broadcast_to(_number_array(k, v), b.shape).reshape(-1) for k, v in
            (("summit_density", summit_density), ("summit_radius", summit_radius),
             ("sigma", sigma), ("radius", radius))]
    out = np.empty(b.n)
    mu = ctypes.c_double()
    for i in range(b.n):
        check(lib.egw_mu_from_summits(float(flat[0][i]), float(flat[1][i]),
                                      float(flat[2][i]), float(flat[3][i]), ctypes.byref(mu)))
        out[i] = mu.value
    return _scalar_or_array(b.shape, out.reshape(b.shape))


def effective_modulus(E1: ArrayLike, nu1: ArrayLike, E2: Optional[ArrayLike] = None,
                      nu2: Optional[ArrayLike] = None) -> FloatOrArray:
    """Effective modulus E* of two elastic bodies, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

    Parameters
    ----------
    E1, nu1 : float or array
        Young's modulus [pressure] (> 0) and Poisson's ratio (in (-1, 0.5]) of body 1.
    E2, nu2 : float or array, optional
        The same for body 2; omitted: the same material as body 1.

    Returns
    -------
    float or ndarray
        E* [pressure], broadcast.

    Raises
    ------
    InvalidArgumentError
        A modulus not finite and > 0, or a Poisson ratio outside (-1, 0.5].
    """
    E2 = E1 if E2 is None else E2
    nu2 = nu1 if nu2 is None else nu2
    vals = {k: _number_array(k, v) for k, v in (("E1", E1), ("nu1", nu1), ("E2", E2),
                                                 ("nu2", nu2))}
    for k in ("E1", "E2"):
        if np.any(~np.isfinite(vals[k]) | (vals[k] <= 0)):
            raise InvalidArgumentError(INVALID_ARGUMENT, f"{k} = {_brief(vals[k])}: must "
                                       "be finite and > 0")
    for k in ("nu1", "nu2"):
        if np.any(~((vals[k] > -1) & (vals[k] <= 0.5))):
            raise InvalidArgumentError(INVALID_ARGUMENT, f"{k} = {_brief(vals[k])}: "
                                       "Poisson's ratio must lie in (-1, 0.5]")
    e = 1.0 / ((1 - vals["nu1"] ** 2) / vals["E1"] + (1 - vals["nu2"] ** 2) / vals["E2"])
    return float(e) if np.ndim(e) == 0 else e


def gauss_integral(n: ArrayLike, h: ArrayLike, derivative: bool = False) -> FloatOrArray:
    """F_n(h) = int_h^inf (s - h)^n phi(s) ds of the standard Gaussian phi, or dF_n/dh.

    Parameters
    ----------
    n : float or array, >= 0
        Order (broadcast with h).
    h : float or array
        Lower limit (a separation in units of sigma).
    derivative : bool
        Return dF_n/dh instead of F_n.

    Returns
    -------
    float or ndarray
        Of the broadcast shape; one C call (egw_gauss_integral_array).

    Raises
    ------
    InvalidArgumentError
        A negative order or NaN limit (the message names the index).
    TypeError
        derivative not True or False ("no" would have meant True).
    """
    derivative = _flag("derivative", derivative)
    b = _Batch(None, order=n, h=h)
    (out,) = b.out(1)
    value, deriv = (None, out) if derivative else (out, None)
    (po, so), (ph, sh) = b.inputs["order"], b.inputs["h"]
    b.run(lambda flags, nf: lib.egw_gauss_integral_array(
        b.n, po, so, ph, sh, *_arr(value, deriv), flags, nf))
    return _scalar_or_array(b.shape, out)


def _of_modulus(c_fn, k: ArrayLike) -> FloatOrArray:
    """c_fn(k, &result) elementwise over the modulus k (ellipk, ellipe)."""
    k = _array(k, "k")
    flat = k.reshape(-1)
    (out,) = _loop(k.shape, 1, lambda i, r: check(c_fn(float(flat[i]), r)))
    return _scalar_or_array(k.shape, out)


def ellipk(k: ArrayLike) -> FloatOrArray:
    """Complete elliptic integral of the first kind K(k) of MODULUS k (not m = k^2).

    Parameters
    ----------
    k : float or array
        Modulus, 0 <= k < 1.

    Returns
    -------
    float or ndarray
        K(k), elementwise (a float for a scalar).

    Raises
    ------
    InvalidArgumentError
        k outside [0, 1) or NaN.
    TypeError
        A non-numeric or masked k.
    """
    return _of_modulus(lib.egw_ellipk, k)


def ellipe(k: ArrayLike) -> FloatOrArray:
    """Complete elliptic integral of the second kind E(k) of MODULUS k (not m = k^2).

    Parameters
    ----------
    k : float or array
        Modulus, 0 <= k < 1.

    Returns
    -------
    float or ndarray
        E(k), elementwise (a float for a scalar).

    Raises
    ------
    InvalidArgumentError
        k outside [0, 1) or NaN.
    TypeError
        A non-numeric or masked k.
    """
    return _of_modulus(lib.egw_ellipe, k)


def hertz(params: Params, delta: ArrayLike) -> Tuple[FloatOrArray, FloatOrArray, FloatOrArray]:
    """Hertz contact of smooth elastic spheres (R and E* of params; other fields unused).

    Parameters
    ----------
    params : Params
        Scalar or array fields, broadcast with delta.
    delta : float or array
        Overlap [length]: > 0 pressed together, <= 0 apart (force 0).

    Returns
    -------
    force, stiffness, contact_radius : float or ndarray
        (4/3) E* sqrt(R) delta^1.5 [force], dP/ddelta = 2 E* a [force/length] and
        a = sqrt(R delta) [length], of the broadcast shape; one C call.

    Raises
    ------
    InvalidArgumentError
        A NaN or infinite delta (the message names its index) or an overflowing force;
        under ``errstate(failed="nan")`` such points are NaN instead.
    """
    b = _Batch(params, delta=delta)
    force, stiffness, radius = b.out(3)
    (pd, sd) = b.inputs["delta"]
    b.run(lambda flags, nf: lib.egw_hertz_array(
        b.params[0], b.params[1], b.n, pd, sd, *_arr(force, stiffness, radius), flags, nf))
    return _scalar_or_array(b.shape, force, stiffness, radius)


def flat_pressure(params: Params, separation: ArrayLike, derivative: bool = False):
    """Nominal pressure p_G(d) of a rough flat on a smooth rigid-backed half-space.

    Parameters
    ----------
    params : Params
        Needs sigma > 0, mu and E* (R only enters through mu; a flat has no R of its own:
        give the mu of the surface, e.g. from :func:`egw.contact_from_topography`).
    separation : float or array
        d, the distance of the flat's reference plane (mean summit plane) from the
        counter-face [length]; < 0 means pressed in.
    derivative : bool
        Also return dp_G/dd (<= 0).

    Returns
    -------
    pressure : float or ndarray
        p_G(d) [pressure], broadcast shape; one C call.
    dpressure : float or ndarray
        dp_G/dd, only when derivative=True.

    Raises
    ------
    InvalidArgumentError
        sigma = 0, or a NaN separation (named with its index).
    TypeError
        derivative not True or False ("no" would have meant True).
    """
    derivative = _flag("derivative", derivative)
    b = _Batch(params, separation=separation)
    pressure, dpressure = b.out(2)
    (ps, ss) = b.inputs["separation"]
    b.run(lambda flags, nf: lib.egw_flat_pressure_array(
        b.params[0], b.params[1], b.n, ps, ss, *_arr(pressure, dpressure), flags, nf))
    return _scalar_or_array(b.shape, *((pressure, dpressure) if derivative else (pressure,)))


def flat_pressure_unload(params: Params, separation: ArrayLike, separation_min: ArrayLike,
                         derivative: bool = False):
    """EP-GW rough flat on unloading/reloading: p_G,u(d, d_min) after the closest approach.

    Parameters
    ----------
    params : Params
        As :func:`flat_pressure` (psi > 0 for plastic summits).
    separation, separation_min : float or array
        d and the closest approach d_min so far [length], broadcast; d <= d_min is the
        loading law.
    derivative : bool
        Also return dp/dd.

    Returns
    -------
    pressure[, dpressure] : float or ndarray

    Raises
    ------
    InvalidArgumentError
        A NaN or infinite separation_min, or as :func:`flat_pressure`.
    TypeError
        derivative not True or False ("no" would have meant True).
    """
    derivative = _flag("derivative", derivative)
    _require("egw_flat_pressure_unload_array")
    b = _Batch(params, separation=separation, separation_min=separation_min)
    pressure, dpressure = b.out(2)
    (ps, ss), (pm, sm) = b.inputs["separation"], b.inputs["separation_min"]
    b.run(lambda flags, nf: lib.egw_flat_pressure_unload_array(
        b.params[0], b.params[1], b.n, ps, ss, pm, sm, *_arr(pressure, dpressure), flags, nf))
    return _scalar_or_array(b.shape, *((pressure, dpressure) if derivative else (pressure,)))
