"""Parameters, errors and the point functions of egw (Hertz, rough flat, rough-sphere
solves, unloading, restitution), vectorised over numpy arrays. Every number comes from the
C library; this module only converts arguments and raises egw's errors as exceptions.

Units: any consistent set (SI: m, Pa, N). delta is the overlap of the undeformed sphere
with the mean summit plane, > 0 overlap, < 0 separation; forces and pressures are positive
in compression.
"""
from __future__ import annotations

import contextlib
import contextvars
import ctypes
import dataclasses
import functools
import inspect
import re
import warnings
from dataclasses import dataclass
from typing import Iterator, Optional, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _capi
from ._capi import lib

#: what the functions take: a number, a sequence of numbers or an array
ArrayLike = Union[float, np.ndarray, list, tuple]
#: what they return: a float for scalar inputs, an array of the broadcast shape otherwise
FloatOrArray = Union[float, NDArray[np.float64]]

#: Status codes (include/egw.h).
OK, INVALID_ARGUMENT, INVALID_PARAMETER, NOT_CONVERGED = 0, 1, 2, 3
IO_ERROR, BAD_FILE, OUT_OF_MEMORY, NULL_POINTER, OUT_OF_RANGE, UNSUPPORTED = 4, 5, 6, 7, 8, 9

MODELS = {"Hertz": 0, "GW": 1, "E-GW": 2, "EP-GW": 3, "flat law": 4}
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
    """A table was evaluated above its last node (values from its deep-overlap asymptote)."""


def _status_name(status: int) -> str:
    names = {OK: "EGW_OK", INVALID_ARGUMENT: "EGW_INVALID_ARGUMENT",
             INVALID_PARAMETER: "EGW_INVALID_PARAMETER", NOT_CONVERGED: "EGW_NOT_CONVERGED",
             IO_ERROR: "EGW_IO_ERROR", BAD_FILE: "EGW_BAD_FILE",
             OUT_OF_MEMORY: "EGW_OUT_OF_MEMORY", NULL_POINTER: "EGW_NULL_POINTER",
             OUT_OF_RANGE: "EGW_OUT_OF_RANGE", UNSUPPORTED: "EGW_UNSUPPORTED"}
    return names.get(status, f"status {status}")


def last_error() -> str:
    """egw's message of the last failing call on this thread.

    Returns
    -------
    str
        The whole message (empty when no call has failed).
    """
    # egw_last_error returns the bytes the whole message needs (length + 1): a size
    # query first, then a buffer of that size (no truncation, whatever its length)
    needed = lib.egw_last_error(None, 0)
    if needed < 1:
        return ""
    buf = ctypes.create_string_buffer(needed)
    lib.egw_last_error(buf, len(buf))
    return buf.value.decode("utf-8", "replace")


def _exception(status: int, message: str) -> Exception:
    """The exception of a non-zero egw status with egw's message."""
    if status in (INVALID_ARGUMENT, INVALID_PARAMETER):
        return InvalidArgumentError(status, message)
    if status == NOT_CONVERGED:
        return NotConvergedError(status, message)
    if status in (IO_ERROR, BAD_FILE):
        return FileError(status, message)
    if status == OUT_OF_MEMORY:
        return MemoryError(message)
    return EgwError(status, message)


def check(status: int, allow_out_of_range: bool = False) -> int:
    """Raise the exception of a non-zero egw status.

    Parameters
    ----------
    status : int
        An EGW_* status returned by the library.
    allow_out_of_range : bool
        EGW_OUT_OF_RANGE becomes an :class:`OutOfRangeWarning` (values were written).

    Returns
    -------
    int
        The status (OK, or OUT_OF_RANGE when allowed).

    Raises
    ------
    InvalidArgumentError, NotConvergedError, FileError, MemoryError, EgwError
        By status, with egw's last error message.
    """
    if status == OK:
        return status
    message = last_error()
    if status == OUT_OF_RANGE and allow_out_of_range:
        warnings.warn(message, OutOfRangeWarning, stacklevel=3)
        return status
    raise _exception(status, message)


def version() -> str:
    """Version of the loaded libegw.

    Returns
    -------
    str
        'major.minor.patch', e.g. '0.1.0'.
    """
    v = lib.egw_get_version()
    return f"{v // 10000}.{v // 100 % 100}.{v % 100}"


#: How a failing point of an array call is reported (see `errstate`).
_FAILED = contextvars.ContextVar("egw_failed", default="raise")
_FAILED_MODES = ("raise", "nan", "warn")


class PointFailedWarning(UserWarning):
    """Points of an array call failed and were returned as NaN (``errstate(failed="warn")``)."""


@contextlib.contextmanager
def errstate(failed: str = "raise") -> Iterator[None]:
    """How array calls report a failing point (a NaN input, a refused value, a solve that
    did not converge), like :func:`numpy.errstate`.

    Parameters
    ----------
    failed : {"raise", "nan", "warn"}
        ``"raise"`` (default): the call raises the point's exception, its message naming
        the point's index. ``"nan"``: the point's outputs are NaN, silently. ``"warn"``: NaN
        and one :class:`PointFailedWarning` with the number of failed points.

    Yields
    ------
    None
        The mode holds inside the ``with`` block (per thread and async task).

    Raises
    ------
    ValueError
        For another mode.

    Examples
    --------
    >>> with egw.errstate(failed="nan"):
    ...     f, k, a = egw.hertz(p, [1e-6, float("nan")])   # f[1] is NaN
    """
    if failed not in _FAILED_MODES:
        raise ValueError(f"failed = {failed!r}: must be one of {_FAILED_MODES}")
    token = _FAILED.set(failed)
    try:
        yield
    finally:
        _FAILED.reset(token)


class IgnoredParameterWarning(UserWarning):
    """A parameter was given that the chosen model does not use (psi > 0 outside EP-GW)."""


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


#: an error message shows at most this many characters of a value (never a whole array)
BRIEF_CHARS = 60


def _brief(value) -> str:
    """A short repr for error messages: a value itself when short, else its type, shape,
    dtype and first elements (a message must never print a whole input array)."""
    text = repr(value)
    if len(text) <= BRIEF_CHARS and "\n" not in text:
        return text
    try:
        a = np.asarray(value)
    except Exception:  # noqa: BLE001 - any object: fall back to its cut repr
        return text[:BRIEF_CHARS] + "..."
    if a.ndim == 0:
        return text[:BRIEF_CHARS] + "..."
    head = ", ".join(repr(x)[:12] for x in a.reshape(-1)[:3].tolist())
    return f"<{type(value).__name__} shape {a.shape} dtype {a.dtype}: {head}, ...>"


def _refuse_masked(name: str, value) -> None:
    """Masked arrays are refused (never a mask dropped silently)."""
    if np.ma.is_masked(value):
        raise TypeError(f"{name}: a masked array with {np.ma.count_masked(value)} masked "
                        "values: egw would compute under the mask; pass the valid values "
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
                          f"model {self.model!r} ignores it", IgnoredParameterWarning,
                          stacklevel=3)

    def _take_flat_law(self) -> None:
        from .flat_law import FlatLaw
        if not isinstance(self.flat_law, FlatLaw):
            raise TypeError(f"flat_law must be an egw.FlatLaw, not "
                            f"{type(self.flat_law).__name__}")
        if self.model not in ("E-GW", "flat law"):
            raise InvalidArgumentError(INVALID_PARAMETER, f"model = {self.model!r} with a "
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
                value = float(a[bad].flat[0]) if a.ndim else float(a)
                rel = ">" if strict else ">="
                raise InvalidArgumentError(
                    INVALID_PARAMETER, f"{name} = {value!r}: must be finite and {rel} {low:g}")
        k = np.asarray(self.hardness_coeff)
        bad = ~((k > 0) & (k < 1))
        if np.any(bad):
            value = k[bad].flat[0] if k.ndim else float(k)
            raise InvalidArgumentError(
                INVALID_PARAMETER, f"hardness_coeff = {value!r}: K must lie in (0, 1)")

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
                idx = np.unravel_index(i, self.shape)
                raise InvalidArgumentError(status, f"index {idx}: {last_error()}")

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
        raise TypeError(f"model = {model!r}: must be one of {list(MODELS)} or 0..4")
    if isinstance(model, str):
        if model not in MODELS:
            raise InvalidArgumentError(
                INVALID_PARAMETER, f"model = {model!r}: must be one of {list(MODELS)}")
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
        InvalidArgumentError
            An unknown method name.
        """
        if isinstance(self.method, str):
            if self.method not in METHODS:
                raise InvalidArgumentError(INVALID_ARGUMENT, f"method = {self.method!r}: "
                                           f"must be one of {list(METHODS)}")
            method = METHODS[self.method]
        else:
            method = int(self.method)
        return _capi.Options(int(self.n_radial), float(self.rel_tol), int(self.max_iter),
                             method, int(self.n_threads))


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


def _array(x: ArrayLike, name: str = "value") -> np.ndarray:
    # np.ascontiguousarray would turn a scalar into shape (1,): keep 0-d as 0-d
    return np.require(_number_array(name, x), requirements="C")


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


_INT_MAX = 2 ** 31 - 1
_POINT = re.compile(r"^point (\d+): ")


class _Batch:
    """The arguments of one array call: the broadcast shape of the parameters and the
    inputs, each input as (pointer, stride) (stride 0: one value for all points), the
    parameters as (pointer, stride), and the references that keep the buffers alive."""

    def __init__(self, params: Optional[Params], **inputs):
        if params is not None and not isinstance(params, Params):
            raise TypeError(f"params must be an egw.Params, not {type(params).__name__}")
        arrays = {name: _number_array(name, x) for name, x in inputs.items()}
        shapes = [a.shape for a in arrays.values()]
        if params is not None:
            shapes.append(params.shape)
        try:
            self.shape = np.broadcast_shapes(*shapes)
        except ValueError as exc:
            raise ValueError(f"{', '.join(list(inputs) + ['params'])} do not broadcast "
                             f"together: {exc}") from None
        self.n = int(np.prod(self.shape, dtype=np.int64))
        if self.n > _INT_MAX:
            raise ValueError(f"{self.n} points: an array call takes at most {_INT_MAX}")
        self._keep = []
        self.inputs = {name: self._input(a) for name, a in arrays.items()}
        if params is not None:
            if params.is_scalar:
                c = params.to_c()
                self._keep.append(c)
                self.params = (ctypes.cast(ctypes.byref(c), _P_PARAMS), 0)
            else:
                block = params.to_struct_array(self.shape)
                self._keep.append(block)
                self.params = (block.ctypes.data_as(_P_PARAMS), 1)

    def _input(self, a: np.ndarray):
        if a.size == 1:
            buf = np.array([a.reshape(())], dtype=np.float64)
            stride = 0
        else:
            buf = np.ascontiguousarray(np.broadcast_to(a, self.shape), dtype=np.float64)
            stride = 1
        self._keep.append(buf)
        return _double_ptr(buf), stride

    def out(self, k: int = 1):
        arrays = [np.empty(self.shape, dtype=np.float64) for _ in range(k)]
        return arrays

    def run(self, call) -> None:
        """call(flags, n_failed_ptr) -> status; raises or warns as errstate says."""
        mode = _FAILED.get()
        n_failed = ctypes.c_int(0)
        status = call(0 if mode == "raise" else 1, ctypes.byref(n_failed))
        if status != OK:
            self._raise(status)
        if mode == "warn" and n_failed.value:
            warnings.warn(f"{n_failed.value} of {self.n} points failed and are NaN",
                          PointFailedWarning, stacklevel=3)

    def _raise(self, status: int) -> None:
        message = last_error()
        m = _POINT.match(message)
        if m and self.shape != ():
            index = tuple(int(i) for i in np.unravel_index(int(m.group(1)), self.shape))
            if len(index) == 1:
                index = index[0]
            message = f"index {index}: " + message[m.end():]
        elif m:
            message = message[m.end():]
        raise _exception(status, message)


def _keyword_only(hint: str = ""):
    """Decorator: the function's keyword-only quantities given positionally raise a
    TypeError that names them (a positional call could swap quantities of one kind)."""
    def wrap(func):
        params = inspect.signature(func).parameters.values()
        n_positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
                           for p in params)
        names = [p.name for p in params if p.kind is p.KEYWORD_ONLY]

        @functools.wraps(func)
        def call(*args, **kwargs):
            if len(args) > n_positional:
                raise TypeError(
                    f"{func.__name__}() takes {', '.join(n + '=' for n in names)} by keyword "
                    f"only (got {len(args)} positional arguments): a positional call could "
                    f"swap quantities of one kind{'; ' + hint if hint else ''}")
            return func(*args, **kwargs)
        return call
    return wrap


def _arr(*arrays: np.ndarray):
    return [None if a is None else _double_ptr(a) for a in arrays]


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
    """
    b = _Batch(None, order=n, h=h)
    (out,) = b.out(1)
    value, deriv = (None, out) if derivative else (out, None)
    (po, so), (ph, sh) = b.inputs["order"], b.inputs["h"]
    b.run(lambda flags, nf: lib.egw_gauss_integral_array(
        b.n, po, so, ph, sh, *_arr(value, deriv), flags, nf))
    return _scalar_or_array(b.shape, out)


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
    k = _array(k, "k")
    flat = k.reshape(-1)
    (out,) = _loop(k.shape, 1, lambda i, r: check(lib.egw_ellipk(float(flat[i]), r)))
    return _scalar_or_array(k.shape, out)


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
    k = _array(k, "k")
    flat = k.reshape(-1)
    (out,) = _loop(k.shape, 1, lambda i, r: check(lib.egw_ellipe(float(flat[i]), r)))
    return _scalar_or_array(k.shape, out)


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
    """
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
    """
    _require("egw_flat_pressure_unload_array")
    b = _Batch(params, separation=separation, separation_min=separation_min)
    pressure, dpressure = b.out(2)
    (ps, ss), (pm, sm) = b.inputs["separation"], b.inputs["separation_min"]
    b.run(lambda flags, nf: lib.egw_flat_pressure_unload_array(
        b.params[0], b.params[1], b.n, ps, ss, pm, sm, *_arr(pressure, dpressure), flags, nf))
    return _scalar_or_array(b.shape, *((pressure, dpressure) if derivative else (pressure,)))


@dataclass
class SolveResult:
    """Results of solves (floats for one point, arrays of the broadcast shape otherwise).

    Attributes
    ----------
    force : total force P [force], >= 0 (compression positive).
    stiffness : dP/ddelta [force/length].
    contact_radius : effective contact radius a* [length].
    max_pressure : largest pressure of the profile [pressure].
    est_rel_err : estimated relative error of the force.
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
    res = _capi.Result()
    failed = 0
    for i, x in enumerate(d.reshape(-1)):
        status = lib.egw_solve_flat_law(ctypes.byref(p), law, o, float(x), ctypes.byref(res))
        if status != OK:
            if _FAILED.get() == "raise":
                message = last_error()
                raise _exception(status, message if d.ndim == 0 else
                                 f"index {np.unravel_index(i, d.shape)}: {message}")
            failed += 1
            continue
        for k, v in enumerate((res.force, res.stiffness, res.contact_radius, res.max_pressure,
                               res.est_rel_err)):
            out[k].reshape(-1)[i] = v
        iters.reshape(-1)[i] = res.iterations
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
            options: Optional[Options] = None) -> Tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Total pressure p(r) and surface deflection w(r) of the solved contact at delta.

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

    Returns
    -------
    pressure, deflection : ndarray
        Flat arrays of len(r) [pressure], [length].

    Raises
    ------
    InvalidArgumentError
        Invalid parameters, a NaN overlap or a negative radius.
    NotConvergedError
        The solve did not converge.
    """
    p = _params(params)
    radii = _array(r, "r").reshape(-1).copy()
    pressure = np.empty_like(radii)
    deflection = np.empty_like(radii)
    check(lib.egw_profile(ctypes.byref(p), _options(options), float(delta), radii.size,
                          _double_ptr(radii), _double_ptr(pressure), _double_ptr(deflection)))
    return pressure, deflection


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
    InvalidArgumentError
        mass, velocity or tolerance out of range (named).
    """
    b = _Batch(params, mass=mass, velocity=velocity)
    duration, step = b.out(2)
    o = _options(options)
    (pm, sm), (pv, sv) = b.inputs["mass"], b.inputs["velocity"]
    tol = float(_number_array("tolerance", tolerance))
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
        One contact (scalar fields) with ``flow_pressure`` p_y >= 0.
    mass : float or array, > 0
        Effective mass m*, 1/m* = 1/m1 + 1/m2 [mass].

    Returns
    -------
    FirstYield
        overlap delta_y and speed v_y; both inf when flow_pressure is 0 (no bulk yield).

    Raises
    ------
    InvalidArgumentError
        params invalid, or mass not finite and > 0 (named).
    TypeError
        params not a scalar egw.Params.
    """
    if not isinstance(params, Params) or not params.is_scalar:
        raise TypeError("params must be one egw.Params with scalar fields")
    m = _array(mass, "mass")
    c = params.to_c()

    def call(i, dy, vy):
        check(lib.egw_first_yield(ctypes.byref(c), float(m.reshape(-1)[i]), dy, vy))

    overlap, speed = _loop(m.shape, 2, call)
    if params.flow_pressure == 0:
        overlap[...] = np.inf    # the C call's DBL_MAX: never
        speed[...] = np.inf
    return FirstYield(*_scalar_or_array(m.shape, overlap, speed))


def _require(name: str) -> None:
    if not _capi.has(name):
        raise NotImplementedError(f"the loaded libegw has no {name} (egw {version()})")


__all__ = ["EgwError", "InvalidArgumentError", "NotConvergedError", "FileError",
           "OutOfRangeWarning", "PointFailedWarning", "IgnoredParameterWarning", "Params",
           "Options", "SolveResult", "Restitution", "TimeStep", "FirstYield", "first_yield",
           "version", "last_error",
           "check", "errstate", "mu_from_summits", "effective_modulus", "gauss_integral",
           "ellipk", "ellipe", "hertz", "flat_pressure", "flat_pressure_unload", "solve",
           "solve_unload", "profile", "restitution", "time_step", "MODELS", "PARAMS_DTYPE",
           "RESULT_DTYPE"]
