"""Parameters, errors and the point functions of egw (Hertz, rough flat, rough-sphere
solves, unloading, restitution), vectorised over numpy arrays. Every number comes from the
C library; this module only converts arguments and raises egw's errors as exceptions.

Units: any consistent set (SI: m, Pa, N). delta is the overlap of the undeformed sphere
with the mean summit plane, > 0 overlap, < 0 separation; forces and pressures are positive
in compression.
"""
from __future__ import annotations

import ctypes
import dataclasses
import warnings
from dataclasses import dataclass
from typing import Optional, Tuple, Union

import numpy as np

from . import _capi
from ._capi import lib

ArrayLike = Union[float, np.ndarray, list, tuple]

#: Status codes (include/egw.h).
OK, INVALID_ARGUMENT, INVALID_PARAMETER, NOT_CONVERGED = 0, 1, 2, 3
IO_ERROR, BAD_FILE, OUT_OF_MEMORY, NULL_POINTER, OUT_OF_RANGE, UNSUPPORTED = 4, 5, 6, 7, 8, 9

MODELS = {"Hertz": 0, "GW": 1, "E-GW": 2, "EP-GW": 3}
METHODS = {"auto": 0, "newton": 1, "picard": 2}


class EgwError(Exception):
    """A refused egw call: `status` is the egw status code, `message` egw's own text
    (it names the offending parameter and its valid range)."""

    def __init__(self, status: int, message: str):
        self.status = status
        self.message = message
        super().__init__(f"{message} [{_status_name(status)}]")


class InvalidArgumentError(EgwError, ValueError):
    """EGW_INVALID_ARGUMENT or EGW_INVALID_PARAMETER."""


class NotConvergedError(EgwError, ArithmeticError):
    """EGW_NOT_CONVERGED: a solve did not reach its tolerance (no value is returned)."""


class FileError(EgwError, OSError):
    """EGW_IO_ERROR or EGW_BAD_FILE."""


class OutOfRangeWarning(UserWarning):
    """A table was evaluated above its last node (values extrapolated linearly)."""


def _status_name(status: int) -> str:
    names = {OK: "EGW_OK", INVALID_ARGUMENT: "EGW_INVALID_ARGUMENT",
             INVALID_PARAMETER: "EGW_INVALID_PARAMETER", NOT_CONVERGED: "EGW_NOT_CONVERGED",
             IO_ERROR: "EGW_IO_ERROR", BAD_FILE: "EGW_BAD_FILE",
             OUT_OF_MEMORY: "EGW_OUT_OF_MEMORY", NULL_POINTER: "EGW_NULL_POINTER",
             OUT_OF_RANGE: "EGW_OUT_OF_RANGE", UNSUPPORTED: "EGW_UNSUPPORTED"}
    return names.get(status, f"status {status}")


def last_error() -> str:
    """egw's message of the last failing call on this thread."""
    # egw_last_error returns the bytes the whole message needs (length + 1): a size
    # query first, then a buffer of that size (no truncation, whatever its length)
    needed = lib.egw_last_error(None, 0)
    if needed < 1:
        return ""
    buf = ctypes.create_string_buffer(needed)
    lib.egw_last_error(buf, len(buf))
    return buf.value.decode("utf-8", "replace")


def check(status: int, allow_out_of_range: bool = False) -> int:
    """Raise the exception of a non-zero egw status; EGW_OUT_OF_RANGE becomes an
    OutOfRangeWarning when allow_out_of_range (values were written)."""
    if status == OK:
        return status
    message = last_error()
    if status == OUT_OF_RANGE and allow_out_of_range:
        warnings.warn(message, OutOfRangeWarning, stacklevel=3)
        return status
    if status in (INVALID_ARGUMENT, INVALID_PARAMETER):
        raise InvalidArgumentError(status, message)
    if status == NOT_CONVERGED:
        raise NotConvergedError(status, message)
    if status in (IO_ERROR, BAD_FILE):
        raise FileError(status, message)
    if status == OUT_OF_MEMORY:
        raise MemoryError(message)
    raise EgwError(status, message)


def version() -> str:
    """Version of the loaded libegw, e.g. '0.1.0'."""
    v = lib.egw_get_version()
    return f"{v // 10000}.{v // 100 % 100}.{v % 100}"


@dataclass
class Params:
    """Parameters of one contact; the fields and defaults of the C struct egw_params
    (egw_params_default): E-GW, R = E = 1, sigma = 0, mu = 1, psi = 0, K = 0.6, rho_p = 54.

    model: 'Hertz', 'GW', 'E-GW', 'EP-GW' (or 0..3); radius: equivalent radius R;
    modulus: effective modulus E*; sigma: std of summit heights (0 = smooth);
    mu: Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta); psi: plasticity index of the
    paper (0 = elastic asperities); hardness_coeff: ZMC K in (0, 1); plastic_ratio: rho_p.
    """
    model: Union[str, int] = "E-GW"
    radius: float = 1.0
    modulus: float = 1.0
    sigma: float = 0.0
    mu: float = 1.0
    psi: float = 0.0
    hardness_coeff: float = 0.6
    plastic_ratio: float = 54.0

    def to_c(self) -> _capi.Params:
        model = self.model
        if isinstance(model, str):
            if model not in MODELS:
                raise InvalidArgumentError(
                    INVALID_PARAMETER, f"model = {model!r}: must be one of {list(MODELS)}")
            model = MODELS[model]
        c = _capi.Params(int(model), *(float(getattr(self, f.name))
                                       for f in dataclasses.fields(self)[1:]))
        return c

    def validate(self) -> None:
        """Raise InvalidArgumentError naming the first invalid field."""
        check(lib.egw_params_validate(ctypes.byref(self.to_c())))

    def replace(self, **changes) -> "Params":
        return dataclasses.replace(self, **changes)


@dataclass
class Options:
    """Solver options (C struct egw_options): n_radial (0 = from rel_tol), rel_tol,
    max_iter (0 = default), method ('auto', 'newton', 'picard' or 0..2), n_threads
    (0 = OpenMP default)."""
    n_radial: int = 0
    rel_tol: float = 1e-6
    max_iter: int = 0
    method: Union[str, int] = "auto"
    n_threads: int = 0

    def to_c(self) -> _capi.Options:
        method = METHODS[self.method] if isinstance(self.method, str) else int(self.method)
        return _capi.Options(int(self.n_radial), float(self.rel_tol), int(self.max_iter),
                             method, int(self.n_threads))


def _params(params: Params) -> ctypes.Structure:
    if not isinstance(params, Params):
        raise TypeError("params must be an egw.Params")
    return params.to_c()


def _options(options: Optional[Options]):
    """A pointer to the C options, or None (NULL: the library's defaults)."""
    return None if options is None else ctypes.byref(options.to_c())


def _array(x: ArrayLike) -> np.ndarray:
    # np.ascontiguousarray would turn a scalar into shape (1,): keep 0-d as 0-d
    return np.require(np.asarray(x, dtype=np.float64), requirements="C")


def _double_ptr(a: np.ndarray):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


def _scalar_or_array(shape, *arrays):
    if shape == ():
        return tuple(float(a.reshape(())) for a in arrays) if len(arrays) > 1 \
            else float(arrays[0].reshape(()))
    return arrays if len(arrays) > 1 else arrays[0]


def _loop(shape, n_out, call):
    """Run call(index, outputs...) for every index of shape; outputs are float arrays."""
    outs = [np.empty(shape, dtype=np.float64) for _ in range(n_out)]
    flat = [o.reshape(-1) for o in outs]
    values = [ctypes.c_double() for _ in range(n_out)]
    refs = [ctypes.byref(v) for v in values]
    for i in range(int(np.prod(shape, dtype=np.int64))):
        call(i, *refs)
        for f, v in zip(flat, values):
            f[i] = v.value
    return outs


def mu_from_summits(summit_density: float, summit_radius: float, sigma: float,
                    radius: float) -> float:
    """mu = (8/3) eta sigma sqrt(2 R beta) from summit density eta [1/length^2], summit
    radius beta, roughness sigma and equivalent radius R."""
    mu = ctypes.c_double()
    check(lib.egw_mu_from_summits(float(summit_density), float(summit_radius), float(sigma),
                                  float(radius), ctypes.byref(mu)))
    return mu.value


def gauss_integral(n: float, h: ArrayLike, derivative: bool = False) -> ArrayLike:
    """F_n(h) = int_h^inf (s - h)^n phi(s) ds (or dF_n/dh), elementwise over h."""
    h = _array(h)
    fn = lib.egw_gauss_integral_deriv if derivative else lib.egw_gauss_integral
    flat = h.reshape(-1)
    (out,) = _loop(h.shape, 1, lambda i, r: check(fn(float(n), float(flat[i]), r)))
    return _scalar_or_array(h.shape, out)


def ellipk(k: ArrayLike) -> ArrayLike:
    """Complete elliptic integral of the first kind K(k) of MODULUS k, 0 <= k < 1."""
    k = _array(k)
    flat = k.reshape(-1)
    (out,) = _loop(k.shape, 1, lambda i, r: check(lib.egw_ellipk(float(flat[i]), r)))
    return _scalar_or_array(k.shape, out)


def ellipe(k: ArrayLike) -> ArrayLike:
    """Complete elliptic integral of the second kind E(k) of MODULUS k, 0 <= k < 1."""
    k = _array(k)
    flat = k.reshape(-1)
    (out,) = _loop(k.shape, 1, lambda i, r: check(lib.egw_ellipe(float(flat[i]), r)))
    return _scalar_or_array(k.shape, out)


def hertz(params: Params, delta: ArrayLike) -> Tuple[ArrayLike, ArrayLike, ArrayLike]:
    """Hertz contact of smooth spheres: (force, stiffness, contact_radius) at delta."""
    p = _params(params)
    d = _array(delta)
    flat = d.reshape(-1)
    outs = _loop(d.shape, 3, lambda i, f, k, a: check(
        lib.egw_hertz(ctypes.byref(p), float(flat[i]), f, k, a)))
    return _scalar_or_array(d.shape, *outs)


def flat_pressure(params: Params, separation: ArrayLike, derivative: bool = False):
    """Nominal pressure p_G(d) of the rough flat at separation d (and dp_G/dd when
    derivative=True, returned as a second value)."""
    p = _params(params)
    d = _array(separation)
    flat = d.reshape(-1)
    outs = _loop(d.shape, 2, lambda i, pr, dp: check(
        lib.egw_flat_pressure_deriv(ctypes.byref(p), float(flat[i]), pr, dp)))
    return _scalar_or_array(d.shape, *(outs if derivative else outs[:1]))


def flat_pressure_unload(params: Params, separation: ArrayLike, separation_min: ArrayLike,
                         derivative: bool = False):
    """EP-GW rough flat on unloading/reloading: p_G,u(d, d_min) after the closest approach
    d_min (broadcast together); dp/dd as a second value when derivative=True."""
    _require("egw_flat_pressure_unload")
    p = _params(params)
    d, dm = np.broadcast_arrays(_array(separation),
                                _array(separation_min))
    fd, fm = d.reshape(-1), dm.reshape(-1)
    outs = _loop(d.shape, 2, lambda i, pr, dp: check(lib.egw_flat_pressure_unload(
        ctypes.byref(p), float(fd[i]), float(fm[i]), pr, dp)))
    return _scalar_or_array(d.shape, *(outs if derivative else outs[:1]))


@dataclass
class SolveResult:
    """Arrays (or floats) of egw_result: force, stiffness dP/ddelta, effective contact
    radius a*, max_pressure, est_rel_err (estimated relative error of the force) and the
    nonlinear iterations of the final solve."""
    force: ArrayLike
    stiffness: ArrayLike
    contact_radius: ArrayLike
    max_pressure: ArrayLike
    est_rel_err: ArrayLike
    iterations: ArrayLike


def _solve_loop(shape, call) -> SolveResult:
    n = int(np.prod(shape, dtype=np.int64))
    fields = ("force", "stiffness", "contact_radius", "max_pressure", "est_rel_err")
    out = {f: np.empty(n) for f in fields}
    iters = np.empty(n, dtype=np.int64)
    res = _capi.Result()
    for i in range(n):
        check(call(i, ctypes.byref(res)))
        for f in fields:
            out[f][i] = getattr(res, f)
        iters[i] = res.iterations
    if shape == ():
        return SolveResult(**{f: float(out[f][0]) for f in fields}, iterations=int(iters[0]))
    return SolveResult(**{f: out[f].reshape(shape) for f in fields},
                       iterations=iters.reshape(shape))


def solve(params: Params, delta: ArrayLike, options: Optional[Options] = None) -> SolveResult:
    """Full rough-sphere solve (elliptic-kernel half-space) at each overlap delta."""
    p = _params(params)
    o = _options(options)
    d = _array(delta)
    flat = d.reshape(-1)
    return _solve_loop(d.shape, lambda i, r: lib.egw_solve(ctypes.byref(p), o,
                                                           float(flat[i]), r))


def solve_unload(params: Params, delta: ArrayLike, delta_max: ArrayLike,
                 options: Optional[Options] = None) -> SolveResult:
    """EP-GW unloading/reloading solve at delta after loading to delta_max (broadcast);
    delta > delta_max is the loading solve. Consecutive points with the same delta_max
    load it once (egw_solve_unload keeps the last history): sweep delta inside a delta_max."""
    _require("egw_solve_unload")
    p = _params(params)
    o = _options(options)
    d, dm = np.broadcast_arrays(_array(delta), _array(delta_max))
    fd, fm = d.reshape(-1), dm.reshape(-1)
    return _solve_loop(d.shape, lambda i, r: lib.egw_solve_unload(
        ctypes.byref(p), o, float(fd[i]), float(fm[i]), r))


def profile(params: Params, delta: float, r: ArrayLike,
            options: Optional[Options] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Total pressure p(r) and surface deflection w(r) of the solved contact at delta."""
    p = _params(params)
    radii = _array(r).reshape(-1).copy()
    pressure = np.empty_like(radii)
    deflection = np.empty_like(radii)
    check(lib.egw_profile(ctypes.byref(p), _options(options), float(delta), radii.size,
                          _double_ptr(radii), _double_ptr(pressure), _double_ptr(deflection)))
    return pressure, deflection


@dataclass
class Restitution:
    """Head-on impact: coefficient of restitution e, work of the loading curve up to the
    maximum overlap (= m* v^2/2) and the energy dissipated (W_load - W_unload)."""
    e: float
    work_load: float
    dissipated: float


def restitution(params: Params, mass: float, velocity: float,
                options: Optional[Options] = None) -> Restitution:
    """Coefficient of restitution of a head-on impact of effective mass m* at approach
    speed v from far apart (e = sqrt(W_unload/W_load))."""
    p = _params(params)
    o = _options(options)
    e = ctypes.c_double()
    if _capi.has("egw_restitution_energy"):
        w_load, w_diss = ctypes.c_double(), ctypes.c_double()
        check(lib.egw_restitution_energy(ctypes.byref(p), o, float(mass), float(velocity),
                                         ctypes.byref(e), ctypes.byref(w_load),
                                         ctypes.byref(w_diss)))
        return Restitution(e.value, w_load.value, w_diss.value)
    _require("egw_restitution")
    check(lib.egw_restitution(ctypes.byref(p), o, float(mass), float(velocity),
                              ctypes.byref(e)))
    work = 0.5 * float(mass) * float(velocity) ** 2
    return Restitution(e.value, work, work * (1.0 - e.value ** 2))


def _require(name: str) -> None:
    if not _capi.has(name):
        raise NotImplementedError(f"the loaded libegw has no {name} (egw {version()})")


__all__ = ["EgwError", "InvalidArgumentError", "NotConvergedError", "FileError",
           "OutOfRangeWarning", "Params", "Options", "SolveResult", "Restitution",
           "version", "last_error", "check", "mu_from_summits", "gauss_integral",
           "ellipk", "ellipe", "hertz", "flat_pressure", "flat_pressure_unload", "solve",
           "solve_unload", "profile", "restitution", "MODELS"]
