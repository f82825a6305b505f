"""The plumbing of an array call: numpy arrays to C pointers, broadcasting, one
failing point's message as a numpy index, keyword-only quantities.
"""
from __future__ import annotations

import ctypes
import functools
import inspect
import re
import warnings
from typing import Optional

import numpy as np

from .errors import OK, PointFailedWarning, _FAILED, _exception, last_error
from .params import ArrayLike, Params, _P_PARAMS, _number_array

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
