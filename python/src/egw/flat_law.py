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
import math
import os
from typing import Optional, Tuple, Union

import numpy as np

from ._capi import lib
from .errors import check, INVALID_ARGUMENT, InvalidArgumentError, _brief, _flag, _require
from .params import ArrayLike, FloatOrArray, _c_scalar, _number_array, Options
from ._calls import _loop, _scalar_or_array
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
                                          int(ua.size), _c_scalar("length", length),
                                          _c_scalar("modulus", modulus),
                                          ctypes.byref(h)))
        return cls(h)

    @classmethod
    def from_psd(cls, q: ArrayLike, C: ArrayLike, modulus: float, *,
                 p_min: Optional[float] = None, p_max: Optional[float] = None) -> "FlatLaw":
        """Persson's law from an isotropic power spectrum (egw_flat_law_from_psd).

        Parameters
        ----------
        q : array of float
            Wavenumbers [rad/length], ascending, > 0.
        C : array of float
            Isotropic 2-D PSD at q [length^4], >= 0, with <h^2> = 2 pi int q C(q) dq
            (:func:`psd_from_heights` gives it for a map).
        modulus : float
            E* of the contact [pressure].
        p_min, p_max : float, optional
            Mean-pressure range of the law's nodes [pressure] (default 1e-6 E* to 1e-1 E*).

        Returns
        -------
        FlatLaw
            With contact areas; its length is the spectrum's rms height.

        Raises
        ------
        InvalidArgumentError
            A bad spectrum or range (the message names it).
        TypeError
            modulus, p_min or p_max not one real number.
        NotImplementedError
            The loaded libegw has no Persson law.
        """
        _require("egw_flat_law_from_psd")
        qa = _nodes("q", q)
        ca = _nodes("C", C, qa.size)
        h = ctypes.c_void_p()
        check(lib.egw_flat_law_from_psd(_ptr(qa), _ptr(ca), int(qa.size),
                                        _c_scalar("modulus", modulus),
                                        _c_scalar("p_min", p_min or 0.0),
                                        _c_scalar("p_max", p_max or 0.0),
                                        ctypes.byref(h)))
        return cls(h)

    @classmethod
    def from_heights(cls, heights: ArrayLike, pixel: float, modulus: float, *,
                     p_min: Optional[float] = None, p_max: Optional[float] = None,
                     n_threads: int = 0) -> "FlatLaw":
        """egw's periodic boundary-element solution of a height map, tabulated as a law
        (egw_flat_law_from_heights).

        Parameters
        ----------
        heights : 2-D array, shape (ny, nx)
            One period of a periodic surface [length], square pixels.
        pixel : float
            Pixel size [length].
        modulus : float
            E* of the contact [pressure].
        p_min, p_max : float, optional
            Mean-pressure range [pressure] (default 1e-6 E* to 1e-1 E*).
        n_threads : int
            OpenMP threads of the solver (0: the default).

        Returns
        -------
        FlatLaw
            With contact areas; its length is the map's rms height.

        Raises
        ------
        InvalidArgumentError
            A bad map or range (NaN pixels, a map that is not 2-D, ...).
        TypeError
            pixel, modulus, p_min or p_max not one real number.
        NotConvergedError
            A load did not converge.
        NotImplementedError
            The loaded libegw has no BEM law.
        """
        _require("egw_flat_law_from_heights")
        z = np.ascontiguousarray(_number_array("heights", heights), dtype=np.float64)
        if z.ndim != 2:
            raise InvalidArgumentError(INVALID_ARGUMENT,
                                       f"heights: a 2-D map is needed (shape {z.shape})")
        ny, nx = z.shape
        o = Options(n_threads=n_threads).to_c()
        h = ctypes.c_void_p()
        check(lib.egw_flat_law_from_heights(_ptr(z), int(nx), int(ny), _c_scalar("pixel", pixel),
                                            _c_scalar("modulus", modulus),
                                            _c_scalar("p_min", p_min or 0.0),
                                            _c_scalar("p_max", p_max or 0.0), ctypes.byref(o),
                                            ctypes.byref(h)))
        return cls(h)

    @classmethod
    def from_topography(cls, top, modulus: float, method: str = "BEM", *,
                        pixel_size=None, unit: Optional[str] = None,
                        p_min: Optional[float] = None, p_max: Optional[float] = None,
                        n_threads: int = 0) -> "FlatLaw":
        """The law of a measured or generated surface, by egw's BEM or Persson's theory.

        Parameters
        ----------
        top : height map source
            Anything :func:`egw.topography.height_map` takes (a SurfaceTopography
            topography, a HeightMap, a numpy array with pixel_size and unit, a file).
            Converted to metres: give modulus and pressures in Pa.
        modulus : float
            E* of the contact [Pa].
        method : {"BEM", "Persson"}
            "BEM": egw's periodic boundary-element solver on the map itself (the map
            must be periodic: a non-periodic map is refused, see Notes); "Persson":
            Persson's theory from the map's radially averaged PSD.
        pixel_size, unit :
            For numpy arrays and plain files (as height_map).
        p_min, p_max : float, optional
            Mean-pressure range [Pa] (default 1e-6 E* to 1e-1 E*).
        n_threads : int
            OpenMP threads of the BEM (0: the default).

        Returns
        -------
        FlatLaw

        Raises
        ------
        ValueError
            An unknown method, a non-periodic map for "BEM", pixels that are not square,
            missing units.

        Notes
        -----
        A non-periodic map (an instrument's) has edges that the periodic BEM would wrap
        onto each other: give it to method="Persson", or make it periodic first (e.g.
        SurfaceTopography's windowing, or a periodic generated surface).
        """
        from .topography import height_map
        if method not in ("BEM", "Persson"):
            raise ValueError(f"method = {_brief(method)}: must be 'BEM' or 'Persson'")
        hm = height_map(top, pixel_size, unit).to_metres()
        z = hm.heights - np.mean(hm.heights)
        if not math.isclose(hm.dx, hm.dy, rel_tol=1e-9):
            raise ValueError(f"pixel sizes dx = {hm.dx:g} m and dy = {hm.dy:g} m differ: "
                             "the BEM and the PSD here need square pixels")
        if method == "Persson":
            q, C = psd_from_heights(z, hm.dx)
            return cls.from_psd(q, C, modulus, p_min=p_min, p_max=p_max)
        if not hm.periodic:
            raise ValueError("the map is not periodic: the periodic BEM would wrap its "
                             "edges onto each other; use method='Persson', or a periodic "
                             "map (periodic=True if it is one)")
        return cls.from_heights(z, hm.dx, modulus, p_min=p_min, p_max=p_max,
                                n_threads=n_threads)

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
            u is not numeric, derivative not True or False.
        InvalidArgumentError
            A NaN u, or one where the law is beyond the doubles (the message names it).
        """
        derivative = _flag("derivative", derivative)
        ua = np.asarray(_number_array("u", u), dtype=np.float64)
        flat, h = ua.reshape(-1), self._ptr
        p, d = _loop(ua.shape, 2, lambda i, rp, rd: check(
            lib.egw_flat_law_pressure(h, float(flat[i]), rp, rd)))
        p, d = _scalar_or_array(ua.shape, p, d)
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
        flat, h = ua.reshape(-1), self._ptr
        (a,) = _loop(ua.shape, 1, lambda i, r: check(
            lib.egw_flat_law_contact_area(h, float(flat[i]), r)))
        return _scalar_or_array(ua.shape, a)

    def __repr__(self) -> str:
        if self._handle is None:
            return "FlatLaw(closed)"
        n, length, modulus, u0, u1, has_area = self._info()
        return (f"FlatLaw({n} nodes, u in [{u0:.4g}, {u1:.4g}], length {length:.4g}, "
                f"modulus {modulus:.4g}, area {'yes' if has_area else 'no'})")


def psd_from_heights(heights: ArrayLike, pixel: float, per_decade: int = 20
                     ) -> Tuple[np.ndarray, np.ndarray]:
    """The isotropic (radially averaged) 2-D power spectrum of a periodic height map, as
    the nodes of a step function that keeps the map's power.

    Parameters
    ----------
    heights : 2-D array
        One period of the surface [length] (its mean is removed).
    pixel : float
        Pixel size [length] (square pixels).
    per_decade : int
        Logarithmic bins of |q| per decade (bins without a mode join the next).

    Returns
    -------
    q, C : arrays
        Nodes for :meth:`FlatLaw.from_psd` [rad/length], [length^4], in Persson's convention
        <h^2> = int d^2q C(q) = 2 pi int q C dq: C is constant on each annulus of |q| from
        2 pi/L to the Nyquist pi/pixel (two nodes per annulus, the second 1e-9 below the
        next), equal to the power of the map's modes in it over the annulus' area, so that
        2 pi int q C dq is the power of every mode inside the Nyquist circle exactly (the
        corners of the square spectrum, beyond it, are dropped).

    Raises
    ------
    InvalidArgumentError
        A map that is not 2-D, or not finite, or a pixel size that is not > 0.
    TypeError
        A pixel size that is not one real number.
    """
    z = np.asarray(_number_array("heights", heights), dtype=np.float64)
    if z.ndim != 2 or not np.all(np.isfinite(z)):
        raise InvalidArgumentError(INVALID_ARGUMENT, "heights: a finite 2-D map is needed")
    pixel = _c_scalar("pixel", pixel)
    if not (math.isfinite(pixel) and pixel > 0):
        raise InvalidArgumentError(INVALID_ARGUMENT, f"pixel = {_brief(pixel)}: must be > 0")
    ny, nx = z.shape
    z = z - z.mean()
    power = np.abs(np.fft.fft2(z)) ** 2 / (nx * ny) ** 2  # |a_k|^2: sum = variance
    qx = 2 * math.pi * np.fft.fftfreq(nx, d=pixel)
    qy = 2 * math.pi * np.fft.fftfreq(ny, d=pixel)
    qq = np.hypot(*np.meshgrid(qx, qy))
    q_min, q_max = 2 * math.pi / (max(nx, ny) * pixel), math.pi / pixel
    keep = (qq > 0) & (qq <= q_max * (1 + 1e-12))
    edges = np.logspace(math.log10(q_min), math.log10(q_max),
                        max(2, int(per_decade * math.log10(q_max / q_min)) + 1))
    edges[0], edges[-1] = q_min * (1 - 1e-6), q_max * (1 + 1e-6)
    idx = np.clip(np.digitize(qq[keep], edges) - 1, 0, edges.size - 2)
    counts = np.bincount(idx, minlength=edges.size - 1)
    sums = np.bincount(idx, power[keep], minlength=edges.size - 1)
    q_nodes, c_nodes = [], []
    lo, acc = edges[0], 0.0
    for i in range(edges.size - 1):
        acc += sums[i]
        if counts[i] == 0 and i < edges.size - 2:
            continue                       # an empty bin joins the next
        hi = edges[i + 1]
        c = acc / (math.pi * (hi ** 2 - lo ** 2)) if acc > 0 else 0.0
        q_nodes += [lo, hi * (1 - 1e-9)]
        c_nodes += [c, c]
        lo, acc = hi, 0.0
    return np.array(q_nodes), np.array(c_nodes)


__all__ = ["FlatLaw", "psd_from_heights"]
