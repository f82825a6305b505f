"""Force tables (one parameter set), universal tables (every R, E, sigma, mu of a model)
and EP-GW hysteresis tables, as owned handles of the C library. A table is evaluated over
a whole numpy array in ONE C call (egw_table_eval_array), so the cost per point is that of
the C evaluation; the tables themselves are built, written and read by the library.
"""
from __future__ import annotations

import ctypes
import os
import warnings
from dataclasses import dataclass
from typing import Optional, Tuple, Union

import numpy as np

from . import _capi
from ._capi import lib
from .errors import check, _brief, _FAILED, OK, OUT_OF_RANGE, PointFailedWarning, _require
from .params import ArrayLike, FloatOrArray, Options, _c_scalar, _options, Params, _params
from ._calls import _array, _Batch, _double_ptr, _scalar_or_array

FORMATS = {"csv": 0, "binary": 1, "lammps": 2, "calculix": 3}
PathLike = Union[str, os.PathLike]


def _format(fmt: Union[str, int]) -> int:
    if isinstance(fmt, str):
        if fmt not in FORMATS:
            raise ValueError(f"format = {_brief(fmt)}: must be one of {list(FORMATS)}")
        return FORMATS[fmt]
    return _c_scalar("format", fmt, True)


def _path(path: PathLike) -> bytes:
    return os.fsencode(path)


class _Handle:
    """An owned C handle, released by the library's free function."""
    _free = None  # name of the C free function

    def __init__(self, handle: ctypes.c_void_p):
        self._handle = handle

    def close(self) -> None:
        """Release the C object now (also done when garbage-collected)."""
        if getattr(self, "_handle", None) is not None and self._handle.value:
            getattr(lib, self._free)(ctypes.byref(self._handle))
        self._handle = None

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: the library may be gone
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def _ptr(self) -> ctypes.c_void_p:
        if self._handle is None or not self._handle.value:
            raise ValueError("the table was closed")
        return self._handle

    # the C file functions of the subclass's tables: reader(path, &handle) and
    # writer(handle, path, format)
    _reader = None
    _writer = None

    @classmethod
    def _read_file(cls, path: PathLike):
        """A new object owning the table that the class's C reader reads from path."""
        _require(cls._reader)
        h = ctypes.c_void_p()
        check(getattr(lib, cls._reader)(_path(path), ctypes.byref(h)))
        return cls(h)

    def _write_file(self, path: PathLike, format: Union[str, int]) -> None:
        """Write the table to path with the class's C writer (atomic there)."""
        _require(self._writer)
        check(getattr(lib, self._writer)(self._ptr, _path(path), _format(format)))

    @classmethod
    def _build_over_overlaps(cls, c_build: str, p: ctypes.Structure, delta_min: float,
                             delta_max: float, rel_tol: float, options: Optional[Options]):
        """A new object owning the table that the C function c_build(&p, o, delta_min,
        delta_max, rel_tol, &handle) builds over the overlaps [delta_min, delta_max] (p:
        the parameters' C struct, converted by the caller)."""
        h = ctypes.c_void_p()
        check(getattr(lib, c_build)(ctypes.byref(p), _options(options),
                                    _c_scalar("delta_min", delta_min),
                                    _c_scalar("delta_max", delta_max),
                                    _c_scalar("rel_tol", rel_tol), ctypes.byref(h)))
        return cls(h)


@dataclass
class TableInfo:
    """Facts about a force table (the C struct egw_table_info).

    Attributes
    ----------
    model : int
        EGW_MODEL_* of the parameters (0 Hertz, 1 GW, 2 E-GW, 3 EP-GW).
    n_nodes : int
        Interpolation nodes.
    cutoff : float
        First node [length]; rough tables give 0 below it (force under 1e-12 P_ref).
    delta_max : float
        Last node [length]; the deep-overlap asymptote above.
    reference_force : float
        P_ref of the cut-off rule [force].
    rel_tol : float
        The requested interpolation tolerance.
    max_force_error, max_stiffness_error : float
        Measured max relative errors at the build's check solves.
    checksum_missing : int
        1: read from a CSV file without its checksum line (only the reader's sanity
        checks vouch for the numbers).
    """
    model: int
    n_nodes: int
    cutoff: float
    delta_max: float
    reference_force: float
    rel_tol: float
    max_force_error: float
    max_stiffness_error: float
    checksum_missing: int


class Table(_Handle):
    """Force table of one parameter set: force and stiffness against the overlap delta,
    built adaptively to rel_tol from full solves (egw_table_build).

    Made by :meth:`build`, :meth:`read` or :meth:`UniversalTable.slice`, never directly;
    released by :meth:`close`, a ``with`` block or the garbage collector.

    Parameters
    ----------
    handle : ctypes.c_void_p
        The C handle (egw_table) this object owns (internal).
    """
    _free = "egw_table_free"
    _reader, _writer = "egw_table_read", "egw_table_write"

    @classmethod
    def build(cls, params: Params, delta_min: float, delta_max: float,
              rel_tol: float = 1e-6, options: Optional[Options] = None) -> "Table":
        """Build the force table of one contact from full solves (egw_table_build).

        Parameters
        ----------
        params : Params
            Scalar fields; with a ``flat_law`` the table of that law
            (egw_table_build_flat_law: delta from the law's reference plane).
        delta_min, delta_max : float
            Overlap range [length] (delta > 0 pressed together, < 0 apart, from the mean
            summit plane); the table starts at the cut-off if that lies lower.
        rel_tol : float
            Interpolation tolerance against solves between nodes (relative).
        options : Options, optional
            Solver options (threads of the solves).

        Returns
        -------
        Table

        Raises
        ------
        InvalidArgumentError, NotConvergedError
        """
        p = _params(params)
        if params.flat_law is not None:
            h = ctypes.c_void_p()
            check(lib.egw_table_build_flat_law(
                ctypes.byref(p), params.flat_law._ptr, _options(options),
                _c_scalar("delta_min", delta_min), _c_scalar("delta_max", delta_max),
                _c_scalar("rel_tol", rel_tol), ctypes.byref(h)))
            return cls(h)
        return cls._build_over_overlaps("egw_table_build", p, delta_min, delta_max, rel_tol,
                                        options)

    @classmethod
    def read(cls, path: PathLike) -> "Table":
        """Read an egw CSV or binary table (format recognised from the file).

        Parameters
        ----------
        path : str or os.PathLike
            The table file.

        Returns
        -------
        Table

        Raises
        ------
        FileError
            The file cannot be opened, or its content is refused (message says what).
        """
        return cls._read_file(path)

    def write(self, path: PathLike, format: Union[str, int] = "binary") -> None:
        """Write atomically (a temporary file renamed on success).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.
        format : {'binary', 'csv', 'lammps', 'calculix'} or int
            The file format (doc/formats.md).

        Raises
        ------
        ValueError
            An unknown format name.
        TypeError
            A format number that is not a whole number (True, 1.5).
        FileError
            The file cannot be written.
        """
        self._write_file(path, format)

    @property
    def info(self) -> TableInfo:
        """Facts about the table (egw_table_get_info): cut-off, range, errors."""
        c = _capi.TableInfo()
        check(lib.egw_table_get_info(self._ptr, ctypes.byref(c)))
        return TableInfo(*(getattr(c, f) for f, _ in c._fields_))

    def eval(self, delta: ArrayLike) -> Tuple[FloatOrArray, FloatOrArray]:
        """Force and stiffness at overlaps delta, one C call for the whole array.

        Parameters
        ----------
        delta : float or array
            Overlap [length] (> 0 pressed together, < 0 apart, from the mean summit plane).

        Returns
        -------
        force, stiffness : float or ndarray
            Of delta's shape [force], [force/length].

        Warns
        -----
        OutOfRangeWarning
            Above the last node (values from the deep-overlap asymptote, doc/theory.md §9).

        Raises
        ------
        TypeError
            A non-numeric or masked delta.
        InvalidArgumentError
            A NaN overlap.
        """
        d = _array(delta, "delta")
        force = np.empty_like(d)
        stiffness = np.empty_like(d)
        if d.size:
            check(lib.egw_table_eval_array(self._ptr, d.size, _double_ptr(d),
                                           _double_ptr(force), _double_ptr(stiffness)),
                  allow_out_of_range=True)
        return _scalar_or_array(d.shape, force, stiffness)

    def eval_all(self, delta: float) -> Tuple[float, float, float, float]:
        """Everything the table knows at one overlap (egw_table_eval_all).

        Parameters
        ----------
        delta : float
            Overlap [length].

        Returns
        -------
        force, stiffness, energy, contact_radius : float
            P [force], dP/ddelta [force/length], the elastic energy int P ddelta from the
            cut-off [energy], and the effective contact radius [length].

        Raises
        ------
        InvalidArgumentError
            A NaN overlap (above the last node: OutOfRangeWarning, extrapolated).
        TypeError
            delta not one real number (an array, a string, a bool).
        """
        out = [ctypes.c_double() for _ in range(4)]
        d = _c_scalar("delta", delta)
        check(lib.egw_table_eval_all(self._ptr, d, *map(ctypes.byref, out)),
              allow_out_of_range=True)
        return tuple(v.value for v in out)


class UniversalTable(_Handle):
    """P/(E sqrt(R) sigma^1.5) over (delta/sigma, mu) for one model: every radius,
    modulus and roughness (egw_universal_build).

    Made by :meth:`build` or :meth:`read`, never directly; released by :meth:`close`,
    a ``with`` block or the garbage collector.

    Parameters
    ----------
    handle : ctypes.c_void_p
        The C handle (egw_universal) this object owns (internal).
    """
    _free = "egw_universal_free"
    _reader, _writer = "egw_universal_read", "egw_universal_write"

    @classmethod
    def build(cls, params: Params, mu_min: float, mu_max: float, x_min: float,
              x_max: float, rel_tol: float = 1e-6,
              options: Optional[Options] = None) -> "UniversalTable":
        """Build the universal table of a model over mu and x = delta/sigma
        (egw_universal_build): P/(E sqrt(R) sigma^1.5) for every R, E*, sigma.

        Parameters
        ----------
        params : Params
            The model (and psi, K, rho_p for EP-GW); R, E*, sigma, mu are scaled out.
        mu_min, mu_max : float
            Range of mu (> 0).
        x_min, x_max : float
            Range of delta/sigma.
        rel_tol : float
            Interpolation tolerance (relative).
        options : Options, optional

        Returns
        -------
        UniversalTable

        Raises
        ------
        InvalidArgumentError, NotConvergedError
        """
        p = _params(params)
        h = ctypes.c_void_p()
        check(lib.egw_universal_build(ctypes.byref(p), _options(options),
                                      _c_scalar("mu_min", mu_min), _c_scalar("mu_max", mu_max),
                                      _c_scalar("x_min", x_min), _c_scalar("x_max", x_max),
                                      _c_scalar("rel_tol", rel_tol), ctypes.byref(h)))
        return cls(h)

    @classmethod
    def read(cls, path: PathLike) -> "UniversalTable":
        """Read a universal table written by :meth:`write`.

        Parameters
        ----------
        path : str or os.PathLike
            The table file.

        Returns
        -------
        UniversalTable

        Raises
        ------
        FileError
            The file cannot be opened, or its content is refused.
        """
        return cls._read_file(path)

    def write(self, path: PathLike, format: Union[str, int] = "binary") -> None:
        """Write atomically (a temporary file renamed on success).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.
        format : {'binary', 'csv'} or int
            The file format (doc/formats.md).

        Raises
        ------
        ValueError
            An unknown format name.
        TypeError
            A format number that is not a whole number (True, 1.5).
        FileError
            The file cannot be written.
        """
        self._write_file(path, format)

    def eval(self, params: Params, delta: ArrayLike) -> Tuple[FloatOrArray, FloatOrArray]:
        """Force and stiffness of contacts read from the table, in one C call.

        Parameters
        ----------
        params : Params
            The contacts: R, E*, sigma (> 0), mu may be arrays (broadcast with delta);
            model, psi, K, rho_p must equal the table's.
        delta : float or array
            Overlap [length] (> 0 pressed together, < 0 apart, from the mean summit plane).

        Returns
        -------
        force, stiffness : float or ndarray
            Of the broadcast shape.

        Warns
        -----
        OutOfRangeWarning
            Points above x_max*sigma (the deep-overlap asymptote) or with mu outside the table
            (NaN there).

        Raises
        ------
        InvalidArgumentError
            A NaN overlap (named with its index), or parameters that do not match the table.
        """
        b = _Batch(params, delta=delta)
        force, stiffness = b.out(2)
        pd, sd = b.inputs["delta"]
        if not _capi.has("egw_universal_eval_array"):
            raise NotImplementedError("the loaded libegw has no egw_universal_eval_array")
        mode = _FAILED.get()
        n_failed = ctypes.c_int(0)
        status = lib.egw_universal_eval_array(self._ptr, b.params[0], b.params[1], b.n, pd,
                                              sd, _double_ptr(force), _double_ptr(stiffness),
                                              0 if mode == "raise" else 1,
                                              ctypes.byref(n_failed))
        if status not in (OK, OUT_OF_RANGE):
            b._raise(status)
        if status == OUT_OF_RANGE:
            check(status, allow_out_of_range=True)
        if mode == "warn" and n_failed.value:
            warnings.warn(f"{n_failed.value} of {b.n} points failed and are NaN",
                          PointFailedWarning, stacklevel=2)
        return _scalar_or_array(b.shape, force, stiffness)

    def slice(self, params: Params, delta_max: Optional[float] = None) -> Table:
        """The 1-D table of one contact cut out of the universal table (no solves).

        Parameters
        ----------
        params : Params
            The contact (scalar fields; model, psi, K, rho_p as the table's, mu inside
            its range).
        delta_max : float, optional
            Trim the slice to the overlaps up to delta_max [length] a scene visits (faster
            lookups); None: the whole range.

        Returns
        -------
        Table

        Raises
        ------
        InvalidArgumentError
            Parameters that do not match the table, or mu outside it.
        """
        p = _params(params)
        h = ctypes.c_void_p()
        if delta_max is None:
            check(lib.egw_universal_slice(self._ptr, ctypes.byref(p), ctypes.byref(h)))
        else:
            check(lib.egw_universal_slice_range(self._ptr, ctypes.byref(p),
                                                _c_scalar("delta_max", delta_max),
                                                ctypes.byref(h)))
        return Table(h)


@dataclass(frozen=True)
class HysteresisInfo:
    """Facts about a hysteresis table (the C struct egw_hysteresis_info).

    Attributes
    ----------
    model : int
        EGW_MODEL_* of the parameters.
    reversible : bool
        No plastic summits: unloading retraces loading.
    n_delta_max, n_s : int
        Grid sizes over delta_max and along each unloading curve (0 when reversible).
    n_loading : int
        Nodes of the loading table.
    cutoff : float
        The loading table's first node [length] (forces under 1e-12 of
        reference_force; 0 below it).
    delta_max : float
        The last delta_max node [length].
    reference_force : float
        P_ref of the loading table [force].
    rel_tol, max_error : float
        Requested tolerance and largest mismatch found at the check solves, both
        relative to the turning point's force P(m) where the cap acts on a rough model
        (gap curves, and since format 6 force-ratio curves on the two-piece map), and
        to the local force down to 1e-3 P(m) on Hertz + cap's force-ratio and
        ln(P_load/P) curves.
        max_error includes delta_max intervals too narrow to split, and exceeds rel_tol
        where those miss it (egw.h, egw_hysteresis_info).
    """
    model: int
    reversible: bool
    n_delta_max: int
    n_s: int
    n_loading: int
    cutoff: float
    delta_max: float
    reference_force: float
    rel_tol: float
    max_error: float


class HysteresisTable(_Handle):
    """EP-GW (or any model + flow-pressure cap) loading/unloading/reloading force over
    (delta, delta_max) for one parameter set (egw_hysteresis_build). The history (the
    largest overlap so far) belongs to the caller: a new contact starts from -inf
    (:meth:`new_state`).

    Made by :meth:`build` or :meth:`read`, never directly; released by :meth:`close`,
    a ``with`` block or the garbage collector.

    Parameters
    ----------
    handle : ctypes.c_void_p
        The C handle (egw_hysteresis) this object owns (internal).
    """
    _free = "egw_hysteresis_free"
    _reader, _writer = "egw_hysteresis_read", "egw_hysteresis_write"

    @classmethod
    def build(cls, params: Params, delta_min: float, delta_max: float,
              rel_tol: float = 1e-4, options: Optional[Options] = None) -> "HysteresisTable":
        """Build the EP-GW loading/unloading table of one contact (egw_hysteresis_build).

        Parameters
        ----------
        params : Params
            Scalar fields, model EP-GW, or Hertz (or sigma = 0) with flow_pressure > 0
            (the flow-pressure cap: unloading from the deformed shape, doc/theory.md
            section 12), or GW, E-GW, EP-GW with flow_pressure > 0 (the rough solver
            caps the total pressure; GW and E-GW dissipate from the rough first yield,
            where the largest total pressure reaches p_y, and are reversible when it
            never does up to delta_max); other models give a reversible table.
        delta_min, delta_max : float
            Overlap range [length], sign as in :func:`egw.solve`.
        rel_tol : float
            Interpolation tolerance (relative).
        options : Options, optional

        Returns
        -------
        HysteresisTable

        Raises
        ------
        InvalidArgumentError, NotConvergedError
        EgwError
            Status UNSUPPORTED: a rough model with the cap at sigma/delta_y <= 1e-4 whose
            delta_max lies beyond 2e5 sigma (plastic summits 1.5e5 sigma), where such
            builds failed after their solves; the message names the routes (a smaller
            delta_max, sigma = 0 for Hertz + cap with its bound, single solves).
        """
        _require("egw_hysteresis_build")
        return cls._build_over_overlaps("egw_hysteresis_build", _params(params), delta_min,
                                        delta_max, rel_tol, options)

    @classmethod
    def read(cls, path: PathLike) -> "HysteresisTable":
        """Read a hysteresis table written by :meth:`write`.

        Parameters
        ----------
        path : str or os.PathLike
            The table file.

        Returns
        -------
        HysteresisTable

        Raises
        ------
        FileError
            The file cannot be opened, or its content is refused.
        NotImplementedError
            The loaded libegw has no hysteresis tables.
        """
        return cls._read_file(path)

    def write(self, path: PathLike, format: Union[str, int] = "binary") -> None:
        """Write atomically (a temporary file renamed on success).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.
        format : {'binary', 'csv'} or int
            The file format (doc/formats.md).

        Raises
        ------
        ValueError
            An unknown format name.
        TypeError
            A format number that is not a whole number (True, 1.5).
        FileError
            The file cannot be written.
        """
        self._write_file(path, format)

    def info(self) -> "HysteresisInfo":
        """Facts about the table (egw_hysteresis_get_info).

        Returns
        -------
        HysteresisInfo

        Raises
        ------
        ValueError
            The table was closed.
        """
        _require("egw_hysteresis_get_info")
        c = _capi.HysteresisInfo()
        check(lib.egw_hysteresis_get_info(self._ptr, ctypes.byref(c)))
        return HysteresisInfo(model=c.model, reversible=bool(c.reversible),
                              n_delta_max=c.n_delta_max, n_s=c.n_s, n_loading=c.n_loading,
                              cutoff=c.cutoff, delta_max=c.delta_max,
                              reference_force=c.reference_force, rel_tol=c.rel_tol,
                              max_error=c.max_error)

    def eval(self, delta: ArrayLike, state: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Force and stiffness of contacts on loading, unloading or reloading: one C call
        for the whole array (egw_hysteresis_eval_array), every element its own contact.

        Parameters
        ----------
        delta : float or array
            Overlaps [length], sign as in :func:`egw.solve`.
        state : ndarray
            The contacts' histories (largest overlap so far; -inf for a new contact:
            :meth:`new_state`): a C-contiguous float64 array of delta's shape, updated in
            place to max(state, delta).

        Returns
        -------
        force, stiffness : ndarray
            Of delta's shape [force], [force/length].

        Warns
        -----
        OutOfRangeWarning
            Overlaps or states above the table's last node (extrapolated; with the
            flow-pressure cap without a bound, 1.6e-2 of the force at 1.25 delta_max: build
            to the deepest overlap, include/egw.h egw_hysteresis_eval). Not for a Hertz +
            cap table to 35 delta_y or more: beyond it the exact fully capped
            continuation, no warning; nor for a rough + cap table to 35 delta_y or more
            up to its measured reach (doc/theory.md section 12, "Beyond a rough + cap
            table").

        Raises
        ------
        TypeError
            A state that is not a C-contiguous float64 array of delta's shape, or a
            masked array.
        InvalidArgumentError
            A NaN overlap.
        """
        d = _array(delta, "delta")
        if not (isinstance(state, np.ndarray) and state.dtype == np.float64
                and state.shape == d.shape and state.flags.c_contiguous) \
                or isinstance(state, np.ma.MaskedArray):
            raise TypeError("state must be a C-contiguous float64 array shaped like delta "
                            "(not a masked array)")
        force = np.empty(d.shape)
        stiffness = np.empty(d.shape)
        if d.size:
            if _capi.has("egw_hysteresis_eval_array"):
                check(lib.egw_hysteresis_eval_array(self._ptr, d.size, _double_ptr(d),
                                                    _double_ptr(state), _double_ptr(force),
                                                    _double_ptr(stiffness)),
                      allow_out_of_range=True)
            else:  # an older libegw: one call per contact
                ff, kf, sf, df = (a.reshape(-1) for a in (force, stiffness, state, d))
                s, f, k = ctypes.c_double(), ctypes.c_double(), ctypes.c_double()
                for i in range(df.size):
                    s.value = sf[i]
                    check(lib.egw_hysteresis_eval(self._ptr, float(df[i]), ctypes.byref(s),
                                                  ctypes.byref(f), ctypes.byref(k)),
                          allow_out_of_range=True)
                    sf[i], ff[i], kf[i] = s.value, f.value, k.value
        return force, stiffness

    def energy(self, delta: ArrayLike, state: ArrayLike) -> np.ndarray:
        """The elastic energy each contact returns if it separates now
        (egw_hysteresis_energy): the integral of its unloading curve, turning point
        max(state, delta), from the cut-off to delta.

        Parameters
        ----------
        delta : float or array
            Overlaps [length].
        state : float or array
            The contacts' histories (broadcast to delta's shape); read, not changed.

        Returns
        -------
        ndarray
            The energies [energy], of delta's shape.

        Raises
        ------
        TypeError
            A non-numeric or masked input.
        InvalidArgumentError
            A NaN overlap.
        """
        d = _array(delta, "delta")
        s = np.broadcast_to(_array(state, "state"), d.shape)
        out = np.empty(d.shape)
        u = ctypes.c_double()
        of, df, sf = out.reshape(-1), d.reshape(-1), s.reshape(-1)
        for i in range(df.size):
            check(lib.egw_hysteresis_energy(self._ptr, float(df[i]), float(sf[i]),
                                            ctypes.byref(u)), allow_out_of_range=True)
            of[i] = u.value
        return out

    @staticmethod
    def new_state(shape=()) -> np.ndarray:
        """Histories of contacts that never touched.

        Parameters
        ----------
        shape : int or tuple of int
            Shape of the array of contacts (() for one).

        Returns
        -------
        ndarray
            float64 filled with -inf, for :meth:`eval`.

        Raises
        ------
        TypeError
            A shape that is not whole numbers (2.5, True, "3"), named.
        ValueError
            A negative size, named.
        """
        dims = [shape] if np.ndim(shape) == 0 else list(np.ravel(shape))
        if not all(isinstance(k, (int, np.integer)) and not isinstance(k, (bool, np.bool_))
                   for k in dims):
            raise TypeError(f"shape = {_brief(shape)}: must be a whole number or a tuple "
                            "of them")
        if any(k < 0 for k in dims):
            raise ValueError(f"shape = {_brief(shape)}: sizes must be >= 0")
        return np.full(shape, -np.inf)


__all__ = ["Table", "TableInfo", "UniversalTable", "HysteresisTable", "HysteresisInfo",
           "FORMATS",
           "OUT_OF_RANGE"]
