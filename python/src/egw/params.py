"""The contact parameters and solver options (the C structs egw_params and
egw_options) and the checks every argument goes through before it reaches C.

Units: any consistent set (SI: m, Pa, N).
"""
from __future__ import annotations

import ctypes
import dataclasses
import warnings
from dataclasses import dataclass
from typing import Optional, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _capi
from ._capi import lib
from .errors import (INVALID_ARGUMENT, INVALID_PARAMETER, IgnoredParameterWarning,
                     InvalidArgumentError, OK, _brief, _point_index, check, last_error)

#: what the functions take: a number, a sequence of numbers or an array
ArrayLike = Union[float, np.ndarray, list, tuple]
#: what they return: a float for scalar inputs, an array of the broadcast shape otherwise
FloatOrArray = Union[float, NDArray[np.float64]]


MODELS = {"Hertz": 0, "GW": 1, "E-GW": 2, "EP-GW": 3, "flat law": 4}
METHODS = {"auto": 0, "newton": 1, "picard": 2}


_FIELDS = ("radius", "modulus", "sigma", "mu", "psi", "hardness_coeff", "plastic_ratio",
           "flow_pressure")
#: numpy layout of the C struct egw_params (int model, 8 doubles, C alignment).
PARAMS_DTYPE = np.dtype([("model", np.int32)] + [(f, np.float64) for f in _FIELDS],
                        align=True)
assert PARAMS_DTYPE.itemsize == ctypes.sizeof(_capi.Params)
#: numpy layout of the C struct egw_result.
RESULT_DTYPE = np.dtype([(f, np.float64) for f in ("force", "stiffness", "contact_radius",
                                                   "max_pressure", "est_rel_err", "residual")]
                        + [("iterations", np.int32), ("method_used", np.int32)], align=True)
assert RESULT_DTYPE.itemsize == ctypes.sizeof(_capi.Result)


def _refuse_masked(name: str, value) -> None:
    """Masked arrays are refused (never a mask dropped silently)."""
    if np.ma.is_masked(value):
        n = int(np.ma.count_masked(value))
        raise TypeError(f"{name}: a masked array with {n} masked value{'' if n == 1 else 's'}"
                        ": egw would compute under the mask; pass the valid values "
                        "(x.compressed()), or x.filled(np.nan) under "
                        "egw.errstate(failed='nan') and np.ma.masked_invalid on the result")


def _number_array(name: str, value) -> np.ndarray:
    """value as float64 (a scalar as 0-d); strings, None, booleans, complex and masked
    arrays with a masked value refused."""
    _refuse_masked(name, value)
    raw = np.asarray(value)
    if raw.dtype.kind not in "iuf":
        got = raw.dtype if raw.dtype.kind != "O" else type(value).__name__
        raise TypeError(f"{name} = {_brief(value)}: must be a real number or an array of "
                        f"real numbers (got {got})")
    return np.asarray(raw, dtype=np.float64)


def _first_bad(name: str, a: np.ndarray, bad: np.ndarray) -> str:
    """'name = value' of a scalar field, 'name[i, ...] = value' of the first bad element of
    an array field (among 1000 values the message says which one; audit29)."""
    if a.ndim == 0:
        return f"{name} = {float(a)!r}"
    index = tuple(int(i) for i in np.argwhere(bad)[0])
    return f"{name}[{', '.join(map(str, index))}] = {float(a[index])!r}"


# (field, lower bound, strict, bound text): the checks egw_params_validate makes first
_BOUNDS = {"radius": (0.0, True), "modulus": (0.0, True), "sigma": (0.0, False),
           "mu": (0.0, True), "psi": (0.0, False), "plastic_ratio": (1.0, True),
           "flow_pressure": (0.0, False)}


@dataclass(eq=False)
class Params:
    """Parameters of a contact: the fields and defaults of the C struct egw_params.

    Every numeric field is a float or an array; arrays broadcast against each other and
    against the overlaps of the functions that take them (numpy rules), so one call
    evaluates many contacts. The parameters are checked here, at construction (and by
    :meth:`replace`): a wrong type raises TypeError, a value out of range
    :class:`InvalidArgumentError` naming the field.

    Parameters
    ----------
    model : {"Hertz", "GW", "E-GW", "EP-GW", "flat law"} or int 0..4
        Contact model (default "E-GW"; "flat law" with a ``flat_law``, which sets it).
    radius : float or array, > 0
        Equivalent radius R = R1 R2/(R1 + R2) [length] (default 1).
    modulus : float or array, > 0
        Effective modulus E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [pressure]
        (default 1; see :func:`effective_modulus`).
    sigma : float or array, >= 0
        Standard deviation of the summit heights of the pair [length]; 0 = smooth (Hertz).
    mu : float or array, > 0 when sigma > 0
        Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta) (dimensionless; default 1).
    psi : float or array, >= 0
        Plasticity index of the summits; used by EP-GW only (a psi > 0 with another model
        warns :class:`IgnoredParameterWarning`).
    hardness_coeff : float or array in (0, 1)
        ZMC coefficient K (H = K x hardness at the onset of yield; default 0.6).
    plastic_ratio : float or array, > 1
        rho_p, fully plastic over initial yield interference (default 54).
    flat_law : FlatLaw, optional
        A rough-flat law (:class:`egw.FlatLaw`: tabulated, Persson, BEM) in place of the
        GW models' law of independent summits: the model becomes "flat law", only radius
        and modulus are used (scalars), sigma is set to the law's length, and delta is the
        overlap with the law's reference plane (the mean plane of the heights).
    flow_pressure : float or array, >= 0
        Bulk flow pressure p_y [pressure] (default 0: no bulk yield): the contact pressure
        is capped at p_y (elastic-perfectly-plastic half-space, doc/theory.md section 12),
        so that loading beyond first yield leaves a residual overlap and impacts lose
        energy. From the yield stress Y, p_y = 1.6 Y (the Hertz first-yield peak). Every
        model: a rough one caps its total pressure in its own solve (doc/theory.md
        section 12, "Rough spheres with the cap"). Must lie below modulus.

    Raises
    ------
    TypeError
        A field is not a real number or array of them (e.g. ``radius="1e-3"``), or model is
        not a str or int.
    InvalidArgumentError
        An unknown model or a value out of its range (also a ValueError).

    Notes
    -----
    The overlap delta of every function is that of the undeformed sphere with the mean
    summit plane: delta > 0 pressed together, delta < 0 apart. Units are any consistent
    set (SI: m, Pa, N).
    """
    model: Union[str, int] = "E-GW"
    radius: FloatOrArray = 1.0
    modulus: FloatOrArray = 1.0
    sigma: FloatOrArray = 0.0
    mu: FloatOrArray = 1.0
    psi: FloatOrArray = 0.0
    hardness_coeff: FloatOrArray = 0.6
    plastic_ratio: FloatOrArray = 54.0
    flat_law: Optional[object] = None
    flow_pressure: FloatOrArray = 0.0

    def __post_init__(self) -> None:
        self.model = _model_name(self.model)
        if self.flat_law is not None:
            self._take_flat_law()
        elif self.model == "flat law":
            raise InvalidArgumentError(INVALID_PARAMETER, "model = 'flat law' needs "
                                       "flat_law = an egw.FlatLaw")
        scalar = True
        for name in _FIELDS:
            a = _number_array(name, getattr(self, name))
            if a.ndim == 0:
                setattr(self, name, float(a))
            else:
                a = a.copy()
                a.setflags(write=False)
                setattr(self, name, a)
                scalar = False
        try:
            self.shape = np.broadcast_shapes(*(np.shape(getattr(self, f)) for f in _FIELDS))
        except ValueError as exc:
            raise InvalidArgumentError(INVALID_PARAMETER, "the array fields of Params do "
                                       f"not broadcast together: {exc}") from None
        self._check_bounds()
        if scalar and self.model != "flat law":
            check(lib.egw_params_validate(ctypes.byref(self.to_c())))
        if self.model != "EP-GW" and np.any(np.asarray(self.psi) > 0):
            warnings.warn(f"psi = {_brief(self.psi)}: the plasticity index is used by EP-GW only; "
                          f"model {_brief(self.model)} ignores it", IgnoredParameterWarning,
                          stacklevel=3)

    def _take_flat_law(self) -> None:
        from .flat_law import FlatLaw
        if not isinstance(self.flat_law, FlatLaw):
            raise TypeError(f"flat_law must be an egw.FlatLaw, not "
                            f"{type(self.flat_law).__name__}")
        if self.model not in ("E-GW", "flat law"):
            raise InvalidArgumentError(INVALID_PARAMETER, f"model = {_brief(self.model)} with a "
                                       "flat_law: the law replaces the model (leave model "
                                       "out, or give 'flat law')")
        self.model = "flat law"
        self.sigma = self.flat_law.length

    def _check_bounds(self) -> None:
        for name, (low, strict) in _BOUNDS.items():
            a = np.asarray(getattr(self, name))
            bad = ~np.isfinite(a) | ((a <= low) if strict else (a < low))
            if name == "mu":  # mu is needed only where sigma > 0
                a, rough = np.broadcast_arrays(a, np.asarray(self.sigma) > 0)
                bad = np.broadcast_to(bad, a.shape) & rough
            if np.any(bad):
                rel = ">" if strict else ">="
                raise InvalidArgumentError(
                    INVALID_PARAMETER, f"{_first_bad(name, a, bad)}: must be finite and {rel} "
                    f"{low:g}")
        k = np.asarray(self.hardness_coeff)
        bad = ~((k > 0) & (k < 1))
        if np.any(bad):
            raise InvalidArgumentError(
                INVALID_PARAMETER, f"{_first_bad('hardness_coeff', k, bad)}: K must lie in (0, 1)")

    @property
    def is_scalar(self) -> bool:
        """True when every field is a single number (one contact)."""
        return self.shape == ()

    def to_c(self) -> _capi.Params:
        """The C struct egw_params of a scalar Params.

        Returns
        -------
        egw._capi.Params

        Raises
        ------
        TypeError
            Params with array fields (use the array functions).
        """
        if not self.is_scalar:
            raise TypeError("Params with array fields has no single C egw_params: "
                            "use the array functions (hertz, solve, ...)")
        return _capi.Params(MODELS[self.model], *(float(getattr(self, f)) for f in _FIELDS))

    def to_struct_array(self, shape: Tuple[int, ...]) -> np.ndarray:
        """The parameters broadcast to shape, as a flat array of the C struct egw_params.

        Parameters
        ----------
        shape : tuple of int
            A shape the fields broadcast to.

        Returns
        -------
        ndarray
            1-D, dtype PARAMS_DTYPE, prod(shape) elements in C order.
        """
        n = int(np.prod(shape, dtype=np.int64))
        block = np.empty(n, dtype=PARAMS_DTYPE)
        block["model"] = MODELS[self.model]
        for name in _FIELDS:
            block[name] = np.broadcast_to(getattr(self, name), shape).reshape(-1)
        return block

    def validate(self) -> None:
        """Check every parameter set with the library (egw_params_validate, which also
        checks the ranges the numerics represent).

        Raises
        ------
        InvalidArgumentError
            Naming the first invalid field (and the index for array fields).
        """
        if self.is_scalar:
            check(lib.egw_params_validate(ctypes.byref(self.to_c())))
            return
        block = self.to_struct_array(self.shape)
        for i in range(block.size):
            status = lib.egw_params_validate(block[i:].ctypes.data_as(_P_PARAMS))
            if status != OK:
                raise InvalidArgumentError(
                    status, f"index {_point_index(i, self.shape)}: {last_error()}")

    def replace(self, **changes) -> "Params":
        """A copy with the given fields changed (checked as at construction).

        Parameters
        ----------
        **changes
            Field names and their new values (model, radius, ...).

        Returns
        -------
        Params

        Raises
        ------
        TypeError, InvalidArgumentError
            As at construction.
        """
        return dataclasses.replace(self, **changes)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Params):
            return NotImplemented
        return self.model == other.model and self.flat_law is other.flat_law and all(
            np.array_equal(getattr(self, f), getattr(other, f)) for f in _FIELDS)


def _model_name(model) -> str:
    if isinstance(model, (bool, np.bool_)) or not isinstance(model, (str, int, np.integer)):
        raise TypeError(f"model = {_brief(model)}: must be one of {list(MODELS)} or 0..4")
    if isinstance(model, str):
        if model not in MODELS:
            raise InvalidArgumentError(
                INVALID_PARAMETER, f"model = {_brief(model)}: must be one of {list(MODELS)}")
        return model
    names = {v: k for k, v in MODELS.items()}
    if int(model) not in names:
        raise InvalidArgumentError(INVALID_PARAMETER,
                                   f"model = {model}: must be 0..4 ({list(MODELS)})")
    return names[int(model)]


@dataclass
class Options:
    """Solver options (C struct egw_options).

    Parameters
    ----------
    n_radial : int
        Radial nodes of the mesh; 0 = chosen from rel_tol.
    rel_tol : float
        Relative tolerance of the force (default 1e-6).
    max_iter : int
        Nonlinear iterations; 0 = the library's default.
    method : {"auto", "newton", "picard"} or 0..2
    n_threads : int
        OpenMP threads; 0 = the OpenMP default. A single solve threads its assembly; an
        array of solves runs its points over the threads, each solve single-threaded.
    """
    n_radial: int = 0
    rel_tol: float = 1e-6
    max_iter: int = 0
    method: Union[str, int] = "auto"
    n_threads: int = 0

    def to_c(self) -> _capi.Options:
        """The C struct egw_options.

        Returns
        -------
        egw._capi.Options

        Raises
        ------
        TypeError
            A field of the wrong type, naming it: rel_tol not a real number, an integer
            field (n_radial, max_iter, method, n_threads) not a whole number (a fraction is
            never truncated), a string, None or a bool.
        InvalidArgumentError
            An unknown method name, or an integer beyond a C int.
        """
        if isinstance(self.method, str):
            if self.method not in METHODS:
                raise InvalidArgumentError(INVALID_ARGUMENT, f"method = {_brief(self.method)}: "
                                           f"must be one of {list(METHODS)}")
            method = METHODS[self.method]
        else:
            method = _c_scalar("method", self.method, True)
        return _capi.Options(_c_scalar("n_radial", self.n_radial, True),
                             _c_scalar("rel_tol", self.rel_tol, False),
                             _c_scalar("max_iter", self.max_iter, True), method,
                             _c_scalar("n_threads", self.n_threads, True))


def _c_scalar(name: str, value, integer: bool = False):
    """One number as a C argument or struct field takes it, value named in a TypeError: one
    real number, or for an integer one whole number within a C int (int() would truncate
    16.5 to 16 silently, float() raise without the name)."""
    _refuse_masked(name, value)
    a = None if isinstance(value, str) else np.asarray(value)
    kind = "an integer" if integer else "a real number"
    if a is None or a.ndim != 0 or a.dtype.kind not in "iuf":
        raise TypeError(f"{name} = {_brief(value)}: must be {kind}")
    x = a.item()
    if not integer:
        return float(x)
    if not float(x).is_integer():
        raise TypeError(f"{name} = {_brief(value)}: must be {kind} (a fraction is not "
                        "truncated)")
    if not -2 ** 31 <= int(x) < 2 ** 31:
        raise InvalidArgumentError(INVALID_ARGUMENT, f"{name} = {_brief(value)}: beyond "
                                   "the range of a C int")
    return int(x)


_P_PARAMS = ctypes.POINTER(_capi.Params)


def _params(params: Params) -> ctypes.Structure:
    """The C struct of a scalar Params (TypeError for anything else)."""
    if not isinstance(params, Params):
        raise TypeError(f"params must be an egw.Params, not {type(params).__name__}")
    return params.to_c()


def _options(options: Optional[Options]):
    """A pointer to the C options, or None (NULL: the library's defaults)."""
    if options is not None and not isinstance(options, Options):
        raise TypeError(f"options must be an egw.Options or None, not {type(options).__name__}")
    return None if options is None else ctypes.byref(options.to_c())
