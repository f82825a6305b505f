"""Statuses, exceptions and warnings of egw: the C library's status codes, the
exception each raises (with the library's message), errstate for array calls.
"""
from __future__ import annotations

import contextlib
import contextvars
import ctypes
import warnings
from typing import Iterator

import numpy as np

from . import _capi
from ._capi import lib

#: Status codes (include/egw.h).
OK, INVALID_ARGUMENT, INVALID_PARAMETER, NOT_CONVERGED = 0, 1, 2, 3
IO_ERROR, BAD_FILE, OUT_OF_MEMORY, NULL_POINTER, OUT_OF_RANGE, UNSUPPORTED = 4, 5, 6, 7, 8, 9


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


def _flag(name: str, value) -> bool:
    """A yes/no argument: True or False (numpy's too, or 0 and 1); anything else named in a
    TypeError (bool() would read "no", 0.5 or an array's truth as True)."""
    if isinstance(value, (bool, np.bool_)) or (
            isinstance(value, (int, np.integer)) and value in (0, 1)):
        return bool(value)
    raise TypeError(f"{name} = {_brief(value)}: must be True or False")


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


def _point_index(flat: int, shape) -> str:
    """A failing point's numpy index as a message shows it: ``3`` in 1-D, ``(1, 0)`` in n-D
    (plain ints: numpy 2's np.int64 reprs would print ``(np.int64(1), ...)``)."""
    index, rest = [], int(flat)
    for n in reversed(tuple(shape)):
        rest, i = divmod(rest, int(n))
        index.insert(0, i)
    return str(index[0]) if len(index) == 1 else str(tuple(index))


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
        raise ValueError(f"failed = {_brief(failed)}: must be one of {_FAILED_MODES}")
    token = _FAILED.set(failed)
    try:
        yield
    finally:
        _FAILED.reset(token)


class IgnoredParameterWarning(UserWarning):
    """A parameter was given that the chosen model does not use (psi > 0 outside EP-GW)."""


def _require(name: str) -> None:
    if not _capi.has(name):
        raise NotImplementedError(f"the loaded libegw has no {name} (egw {version()})")
