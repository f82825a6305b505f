"""Progress reports of long calls: `set_progress(callback)` (C egw_set_progress).

A solve of a rough sphere with the flow-pressure cap at sigma/delta_y <= 1e-6, a
restitution there or a table build can take from seconds to minutes; with a callback set,
egw calls ``callback(done, stage)`` as such a call proceeds on this thread: ``done`` a float
in [0, 1] that never decreases within one call (0 at its start, 1 at its end), ``stage`` a
short name of the step ("history", "small-sigma route: wide histories", "unloading",
"restitution: loading", "table build" ...). ``set_progress(None)`` switches reports off
(the default: egw never prints).

The callback is per thread, as the C hook is: set it on the thread that makes the calls.
Scalar calls report; a call on an array of more than one point runs over OpenMP threads
and reports nothing.
It runs inside the egw call (keep it short); an exception it raises cannot cross the C
library and is reported by ctypes and ignored, the call going on.
"""
from __future__ import annotations

import threading
from typing import Callable, Optional

from ._capi import PROGRESS_FN, has, lib
from .errors import _brief

__all__ = ["set_progress"]

_local = threading.local()


def set_progress(callback: Optional[Callable[[float, str], None]]) -> None:
    """Report progress of this thread's long calls to ``callback(done, stage)``; None: off.

    Parameters
    ----------
    callback : callable(done: float, stage: str) or None
        Called during this thread's long calls (solves, restitution, table builds) with
        the fraction done in [0, 1] (never decreasing within one call, 0 first and 1
        last) and a short stage name; None switches reports off (the default).

    Raises
    ------
    TypeError
        callback is neither callable nor None.
    NotImplementedError
        The loaded libegw has no egw_set_progress.

    Examples
    --------
    >>> import egw
    >>> seen = []
    >>> egw.set_progress(lambda done, stage: seen.append(done))
    >>> egw.set_progress(None)
    """
    if not has("egw_set_progress"):
        raise NotImplementedError("set_progress: this libegw has no egw_set_progress "
                                  "(older than the Python package)")
    if callback is not None and not callable(callback):
        raise TypeError(f"callback = {_brief(callback)}: must be callable(done, stage) or None")
    # (a callback may call set_progress: the C thunk it runs in must outlive that call,
    # so one replaced from inside a callback is kept until the next set_progress outside)
    running = getattr(_local, "running", 0) > 0
    retired = getattr(_local, "retired", [])
    if running:
        retired.append(getattr(_local, "hook", None))
    else:
        retired = []
    _local.retired = retired
    if callback is None:
        lib.egw_set_progress(PROGRESS_FN(), None)
        _local.hook = None
        return

    def hook(done: float, stage: bytes, _user: object) -> None:
        _local.running = getattr(_local, "running", 0) + 1
        try:
            callback(float(done), stage.decode("utf-8", "replace"))
        finally:
            _local.running -= 1

    c_hook = PROGRESS_FN(hook)
    # (kept alive on this thread as long as the library holds it)
    _local.hook = c_hook
    lib.egw_set_progress(c_hook, None)
