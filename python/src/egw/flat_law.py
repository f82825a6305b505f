"""Rough-flat laws beyond GW (doc/theory.md section 11): the mean pressure p of a rough
flat pressed onto a smooth rigid flat against their mean separation u, as an owned handle
of the C library (egw_flat_law). A law is used by the sphere solve and the 1-D table in
place of GW's law of independent summits: give it to :class:`egw.Params` as ``flat_law``.

Sign conventions: u > 0 apart, measured from the law's reference plane (the mean plane of
the heights for a tabulated, Persson or BEM law); p >= 0 compressive; dp/du <= 0. Units
are the caller's (any consistent set, SI suggested).
"""
from __future__ import annotations

import ctypes
import os
from typing import Optional, Tuple, Union

import numpy as np

from ._capi import lib
from .core import (OK, ArrayLike, FloatOrArray, InvalidArgumentError, INVALID_ARGUMENT,
                   _number_array, check)
from .tables import _Handle


def _nodes(name: str, value, n: Optional[int] = None) -> np.ndarray:
    a = np.ascontiguousarray(_number_array(name, value), dtype=np.float64)
    if a.ndim != 1:
        raise InvalidArgumentError(INVALID_ARGUMENT,
                                   f"{name}: a 1-D array is needed (shape {a.shape})")
    if n is not None and a.size != n:
        raise InvalidArgumentError(INVALID_ARGUMENT,
                                   f"{name}: {a.size} values, u has {n}")
    return a


def _ptr(a: Optional[np.ndarray]):
    return None if a is None else a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


class FlatLaw(_Handle):
    """A rough-flat law p(u) (egw_flat_law): mean pressure against mean separation.

    Made by :meth:`from_table` (and, where the library has them, from a power spectrum by
    Persson's theory or from a height map by egw's boundary-element solver). Read-only
    once made; pickling is not supported (it is a C object).
    """
    _free = "egw_flat_law_free"

    @classmethod
    def from_table(cls, u: ArrayLike, p: ArrayLike, *, dpdu: Optional[ArrayLike] = None,
                   area: Optional[ArrayLike] = None, length: float = 0.0,
                   modulus: float = 0.0) -> "FlatLaw":
        """A tabulated law (egw_flat_law_from_table).

        Parameters
        ----------
        u : array of float
            Mean separations [length], strictly ascending (>= 2 nodes).
        p : array of float
            Mean pressures [pressure] at u, > 0 and strictly decreasing.
        dpdu : array of float, optional
            dp/du at the nodes (<= 0); without it the slopes come from the nodes.
        area : array of float, optional
            Contact-area fraction in [0, 1] at the nodes (for :meth:`contact_area`).
        length : float
            The law's natural length [length], the sphere solve's unit (the surface's rms
            height); 0: the decay length -1/(d ln p/du) at the last node.
        modulus : float
            E* the law was computed with (0: not known; else the sphere must have it).

        Returns
        -------
        FlatLaw

        Raises
        ------
        TypeError
            A non-numeric input.
        InvalidArgumentError
            A table the library refuses (the message names the node, e.g. ``u(3)``).

        Notes
        -----
        Between nodes a monotone cubic Hermite in (u, ln p); beyond both ends ln p goes on
        linearly with the end slope (p ~ exp(-u/u0), the large-separation law of Persson's
        theory and of BEM).
        """
        ua = _nodes("u", u)
        pa = _nodes("p", p, ua.size)
        da = None if dpdu is None else _nodes("dpdu", dpdu, ua.size)
        aa = None if area is None else _nodes("area", area, ua.size)
        h = ctypes.c_void_p()
        check(lib.egw_flat_law_from_table(_ptr(ua), _ptr(pa), _ptr(da), _ptr(aa),
                                          int(ua.size), float(length), float(modulus),
                                          ctypes.byref(h)))
        return cls(h)

    @classmethod
    def read(cls, path) -> "FlatLaw":
        """Read a law file (egw_flat_law_read): egw's CSV (:meth:`write`), or a CSV of
        one's own whose first line names the columns ``u`` and ``pressure`` (optionally
        ``dpdu``, ``area``), with optional ``# length = ...`` and ``# modulus = ...``
        lines.

        Parameters
        ----------
        path : str or os.PathLike

        Returns
        -------
        FlatLaw

        Raises
        ------
        FileError
            The file cannot be read or is malformed (the message names the line or node).
        """
        h = ctypes.c_void_p()
        check(lib.egw_flat_law_read(os.fsencode(path), ctypes.byref(h)))
        return cls(h)

    def write(self, path) -> None:
        """Write the law as egw CSV, atomically (egw_flat_law_write).

        Parameters
        ----------
        path : str or os.PathLike

        Returns
        -------
        None

        Raises
        ------
        FileError
            The file cannot be written (an existing file is left as it was).
        """
        check(lib.egw_flat_law_write(self._ptr, os.fsencode(path)))

    def _info(self) -> Tuple[int, float, float, float, float, int]:
        n, has_area = ctypes.c_int(), ctypes.c_int()
        vals = [ctypes.c_double() for _ in range(4)]
        check(lib.egw_flat_law_info(self._ptr, ctypes.byref(n), *(ctypes.byref(v)
                                                                  for v in vals),
                                    ctypes.byref(has_area)))
        return n.value, vals[0].value, vals[1].value, vals[2].value, vals[3].value, \
            has_area.value

    @property
    def length(self) -> float:
        """The law's natural length [length] (the sphere solve's unit of separation)."""
        return self._info()[1]

    @property
    def modulus(self) -> float:
        """E* the law was computed with (0: not known)."""
        return self._info()[2]

    @property
    def separation_range(self) -> Tuple[float, float]:
        """(u_min, u_max) of the nodes [length]; beyond them the law is extrapolated."""
        info = self._info()
        return info[3], info[4]

    @property
    def has_area(self) -> bool:
        """Whether the law carries contact-area fractions (:meth:`contact_area`)."""
        return bool(self._info()[5])

    def pressure(self, u: ArrayLike, derivative: bool = False
                 ) -> Union[FloatOrArray, Tuple[FloatOrArray, FloatOrArray]]:
        """Mean pressure at mean separation u (egw_flat_law_pressure).

        Parameters
        ----------
        u : float or array
            Mean separation [length] from the law's reference plane (the mean plane of
            the heights); any shape.
        derivative : bool
            Also return dp/du.

        Returns
        -------
        float or array, or (p, dp/du)
            Of u's shape (a float for a scalar u).

        Raises
        ------
        TypeError
            u is not numeric.
        InvalidArgumentError
            A NaN u, or one where the law is beyond the doubles (the message names it).
        """
        ua = np.asarray(_number_array("u", u), dtype=np.float64)
        p = np.empty(ua.shape)
        d = np.empty(ua.shape)
        pv, dv = ctypes.c_double(), ctypes.c_double()
        h = self._ptr
        for i, x in enumerate(ua.reshape(-1)):
            status = lib.egw_flat_law_pressure(h, float(x), ctypes.byref(pv), ctypes.byref(dv))
            if status != OK:
                check(status)
            p.reshape(-1)[i] = pv.value
            d.reshape(-1)[i] = dv.value
        if ua.ndim == 0:
            p, d = float(p), float(d)
        return (p, d) if derivative else p

    def contact_area(self, u: ArrayLike) -> FloatOrArray:
        """Contact-area fraction A/A0 in [0, 1] at u (egw_flat_law_contact_area).

        Parameters
        ----------
        u : float or array
            Mean separation [length].

        Returns
        -------
        float or array
            Of u's shape.

        Raises
        ------
        EgwError
            The law carries no contact areas (status UNSUPPORTED), or a NaN u.
        """
        ua = np.asarray(_number_array("u", u), dtype=np.float64)
        a = np.empty(ua.shape)
        av = ctypes.c_double()
        h = self._ptr
        for i, x in enumerate(ua.reshape(-1)):
            check(lib.egw_flat_law_contact_area(h, float(x), ctypes.byref(av)))
            a.reshape(-1)[i] = av.value
        return float(a) if ua.ndim == 0 else a

    def __repr__(self) -> str:
        if self._handle is None:
            return "FlatLaw(closed)"
        n, length, modulus, u0, u1, has_area = self._info()
        return (f"FlatLaw({n} nodes, u in [{u0:.4g}, {u1:.4g}], length {length:.4g}, "
                f"modulus {modulus:.4g}, area {'yes' if has_area else 'no'})")


__all__ = ["FlatLaw"]
