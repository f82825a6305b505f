"""Height maps: the HeightMap type, reading maps from files, arrays and SurfaceTopography
objects with their units, detrending, sum surfaces and coarse-graining, and the
defaults (DEFAULTS) the Python functions and egw-topo share."""
from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass
from typing import Any, Optional, Tuple, Union

import numpy as np

from .errors import _brief, _flag


#: length units a map may carry, in metres
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9,
                "pm": 1e-12, "A": 1e-10, "Å": 1e-10, "cm": 1e-2, "km": 1e3}


@dataclass
class HeightMap:
    """A height map: heights z[i, j] (rows along y, columns along x) on a grid of pixel
    size (dx, dy).

    Attributes
    ----------
    heights : ndarray, shape (ny, nx)
        Heights [unit].
    dx, dy : float
        Pixel sizes [unit], > 0.
    unit : str or None
        The length unit of the heights AND the pixel sizes (a key of LENGTH_UNITS);
        None = unknown (the contact functions refuse such a map).
    periodic : bool
        The map is one period of a periodic surface (detrended by its mean only, FFT
        derivatives, summits found across the edges).
    """
    heights: np.ndarray
    dx: float
    dy: float
    unit: Optional[str] = None
    periodic: bool = False

    def to_metres(self) -> "HeightMap":
        """The same map in metres.

        Returns
        -------
        HeightMap
            Heights and pixel sizes scaled to metres, unit 'm'.

        Raises
        ------
        ValueError
            The map has no unit or an unknown one.
        """
        factor = _unit_factor(self.unit)
        return HeightMap(self.heights * factor, self.dx * factor, self.dy * factor, "m",
                         self.periodic)

    @property
    def area(self) -> float:
        """Area of the map [unit^2]."""
        ny, nx = self.heights.shape
        return nx * self.dx * ny * self.dy


def read_height_map(path: str, pixel_size: Union[float, Tuple[float, float]] = 1.0,
                    unit: Optional[str] = None, periodic: bool = False) -> HeightMap:
    """Read a height map: `.npy` (numpy), `.csv` (comma-separated rows) or a plain-text
    matrix (whitespace-separated rows); '#' lines are comments. Instrument formats:
    :func:`height_map` (through SurfaceTopography).

    Parameters
    ----------
    path : str
        The file.
    pixel_size : float or (dx, dy)
        In the unit of the heights.
    unit : str, optional
        Recorded on the map (None = unknown: the contact functions refuse it).
    periodic : bool
        The map is one period of a periodic surface.

    Returns
    -------
    HeightMap

    Raises
    ------
    ValueError
        Not a 2-D matrix of at least 3 x 3, NaN or infinite pixels, a bad pixel size or
        an unknown unit.
    OSError
        The file cannot be read.
    TypeError
        periodic not True or False ("no" would have meant True).
    """
    periodic = _flag("periodic", periodic)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".npy":
        z = np.load(path, allow_pickle=False)
    else:
        z = np.loadtxt(path, delimiter="," if ext == ".csv" else None, comments="#", ndmin=2)
    z = np.asarray(z, dtype=np.float64)
    _check_shape(z, path)
    if not np.all(np.isfinite(z)):
        raise ValueError(f"{path}: the height map has {np.count_nonzero(~np.isfinite(z))} "
                         "non-finite values (fill or crop missing data first)")
    return _on_grid(z, pixel_size, unit, periodic, path)


def detrend(surface: HeightMap, mode: Optional[str] = None) -> HeightMap:
    """Remove the mean ('mean') or the least-squares plane ('plane') of the heights.

    Parameters
    ----------
    surface : HeightMap
        The map.
    mode : {'mean', 'plane'}, optional
        None (default): 'mean' for a periodic map (a plane would break its periodicity
        and inflate the spectral moments), 'plane' otherwise; the shared default of the
        CLI and Python (see DEFAULTS).

    Returns
    -------
    HeightMap
        The detrended map (the same grid, unit and periodicity).

    Raises
    ------
    ValueError
        Another mode.
    """
    mode = mode or default_detrend(surface.periodic)
    z = surface.heights
    if mode == "mean":
        return dataclasses.replace(surface, heights=z - z.mean())
    if mode != "plane":
        raise ValueError(f"mode = {_brief(mode)}: must be 'plane' or 'mean'")
    ny, nx = z.shape
    y, x = np.mgrid[0:ny, 0:nx]
    a = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return dataclasses.replace(surface, heights=z - (a @ coef).reshape(z.shape))


def sum_surface(a: HeightMap, b: HeightMap) -> HeightMap:
    """The sum surface z1 + z2 of two maps on the same grid (GW's equivalent rough
    surface against a smooth one; its moments are the sums for independent surfaces).

    Parameters
    ----------
    a, b : HeightMap
        Maps of the same shape, pixel size and unit.

    Returns
    -------
    HeightMap
        Periodic when both are.

    Raises
    ------
    ValueError
        Different shapes, pixel sizes or units.
    """
    if a.heights.shape != b.heights.shape or (a.dx, a.dy) != (b.dx, b.dy):
        raise ValueError("sum_surface: the two maps need the same shape and pixel size")
    if a.unit != b.unit:
        raise ValueError(f"sum_surface: the maps are in {_brief(a.unit)} and {_brief(b.unit)}: "
                         "convert one (HeightMap.to_metres)")
    return HeightMap(a.heights + b.heights, a.dx, a.dy, a.unit, a.periodic and b.periodic)


#: The one set of defaults of egw-topo and of the Python functions: periodic maps are
#: detrended by their mean and differentiated by FFT; other maps lose their best-fit plane
#: and use central differences.
DEFAULTS = {"detrend": {True: "mean", False: "plane"},
            "derivatives": {True: "fft", False: "difference"}}


def default_detrend(periodic: bool) -> str:
    """The default detrending (DEFAULTS).

    Parameters
    ----------
    periodic : bool
        Whether the map is periodic.

    Returns
    -------
    str
        'mean' for a periodic map, 'plane' otherwise.
    """
    return DEFAULTS["detrend"][bool(periodic)]


def default_derivatives(periodic: bool) -> str:
    """The default derivatives (DEFAULTS).

    Parameters
    ----------
    periodic : bool
        Whether the map is periodic.

    Returns
    -------
    str
        'fft' for a periodic map, 'difference' otherwise.
    """
    return DEFAULTS["derivatives"][bool(periodic)]


#: Bound on a map's scales (in its own unit): pixel sizes in [1/MAP_SCALE, MAP_SCALE],
#: heights and the curvature scale max|z|/min(dx, dy)**2 at most MAP_SCALE, so that the
#: pixel area, the moments m2 ~ (z/dx)**2, m4 ~ (z/dx**2)**2 and the summit density stay
#: finite doubles (a pixel size of 1e-300 divided by zero, 1e300 overflowed).
MAP_SCALE = 1e100


def _check_scales(z: np.ndarray, dx: float, dy: float, what: str) -> None:
    if not (1.0 / MAP_SCALE <= min(dx, dy) and max(dx, dy) <= MAP_SCALE):
        raise ValueError(f"pixel_size = ({dx:g}, {dy:g}): must lie in "
                         f"[{1.0 / MAP_SCALE:g}, {MAP_SCALE:g}] (in the unit of the heights;"
                         " beyond, the moments and the summit density leave the doubles)")
    top = float(np.max(np.abs(z)))
    if top > MAP_SCALE or top / min(dx, dy) ** 2 > MAP_SCALE:
        raise ValueError(f"{what}: heights up to {top:g} on pixel_size = ({dx:g}, {dy:g}):"
                         f" the heights and the curvature scale max|z|/min(dx, dy)**2 must "
                         f"be at most {MAP_SCALE:g} (the moments leave the doubles)")


def _check_unit(unit: Optional[str]) -> None:
    if unit is not None and unit not in LENGTH_UNITS:
        raise ValueError(f"unit = {_brief(unit)}: must be one of {sorted(set(LENGTH_UNITS))}")


def _unit_factor(unit: Optional[str]) -> float:
    if unit is None:
        raise ValueError("the height map has no unit: give unit= (the length unit of the "
                         f"heights and pixel sizes, one of {sorted(set(LENGTH_UNITS))})")
    _check_unit(unit)
    return LENGTH_UNITS[unit]


def _is_surface_topography(source: Any) -> bool:
    return hasattr(source, "heights") and hasattr(source, "physical_sizes") and \
        hasattr(source, "nb_grid_pts")


def _from_surface_topography(top: Any, unit: Optional[str],
                             periodic: Optional[bool]) -> HeightMap:
    if getattr(top, "dim", 2) != 2:
        raise ValueError(f"a SurfaceTopography of dimension {top.dim}: egw needs an areal "
                         "(2-D) map")
    if getattr(top, "has_undefined_data", False):
        raise ValueError("the topography has undefined (NaN) pixels: fill them "
                         "(top.interpolate_undefined_data()) or crop them first")
    top_unit = getattr(top, "unit", None)
    if top_unit is not None and unit is not None and top_unit != unit:
        raise ValueError(f"mixed units: the topography is in {_brief(top_unit)}, "
                         f"unit = {_brief(unit)} "
                         "was given: convert the topography (top.to_unit(...)) instead")
    unit = top_unit if top_unit is not None else unit
    if unit is None:
        raise ValueError("the topography has no unit: give unit= (or make it with unit=...)")
    _check_unit(unit)
    nx, ny = top.nb_grid_pts
    sx, sy = top.physical_sizes
    heights = np.asarray(top.heights(), dtype=np.float64).T  # ST: [x, y]; egw: [y, x]
    if periodic is None:
        periodic = bool(getattr(top, "is_periodic", False))
    return _checked_map(heights, (sx / nx, sy / ny), unit, periodic, "the topography")


def _checked_map(heights: np.ndarray, pixel_size, unit: Optional[str], periodic: bool,
                 what: str) -> HeightMap:
    if np.ma.is_masked(heights):
        n = int(np.ma.count_masked(heights))
        raise ValueError(f"{what}: a masked array with {n} masked pixel{'' if n == 1 else 's'}"
                         ": masked pixels are missing data; fill or crop them first "
                         "(summits and moments are undefined next to them)")
    raw = np.asarray(heights)
    if raw.dtype.kind not in "iuf":   # float64 would read True as 1, "1" as 1, 1+2j as 1
        raise ValueError(f"{what}: heights must be real numbers (got dtype {raw.dtype})")
    z = raw.astype(np.float64)
    _check_shape(z, what)
    bad = np.count_nonzero(~np.isfinite(z))
    if bad:
        raise ValueError(f"{what}: {bad} NaN or infinite pixels: fill or crop missing "
                         "data first (summits and moments are undefined next to them)")
    if pixel_size is None:
        raise ValueError(f"{what}: give pixel_size (dx or (dx, dy), in the unit of the "
                         "heights)")
    return _on_grid(z, pixel_size, unit, periodic, what)


def _check_shape(z: np.ndarray, what: str) -> None:
    """Refuse heights that are not a 2-D matrix of at least 3 x 3 (what: their source)."""
    if z.ndim != 2 or min(z.shape) < 3:
        raise ValueError(f"{what}: a height map must be a 2-D matrix of at least 3 x 3 "
                         f"values (got shape {z.shape})")


def _on_grid(z: np.ndarray, pixel_size, unit: Optional[str], periodic: bool,
             what: str) -> HeightMap:
    """The HeightMap of the finite heights z on pixels of pixel_size (dx or (dx, dy)),
    after the checks of the pixel size, the scales and the unit (what: their source)."""
    # numbers only: a word, a boolean or a third size is refused, not read as a number
    try:
        sizes = [pixel_size] if np.isscalar(pixel_size) else list(np.ravel(pixel_size))
    except ValueError:   # a ragged sequence
        sizes = []
    if len(sizes) not in (1, 2) or not all(
            isinstance(v, (int, float, np.integer, np.floating)) and
            not isinstance(v, (bool, np.bool_)) for v in sizes):
        raise ValueError(f"pixel_size = {_brief(pixel_size)}: must be dx or (dx, dy), "
                         "real numbers")
    dx, dy = float(sizes[0]), float(sizes[-1])
    if not (dx > 0 and dy > 0 and math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError(f"pixel_size = {_brief(pixel_size)}: must be finite and > 0")
    _check_scales(z, float(dx), float(dy), what)
    _check_unit(unit)
    return HeightMap(z, float(dx), float(dy), unit, bool(periodic))


def height_map(source: Any, pixel_size: Union[None, float, Tuple[float, float]] = None,
               unit: Optional[str] = None, *, height_unit: Optional[str] = None,
               periodic: Optional[bool] = None) -> HeightMap:
    """A HeightMap from a numpy array, a SurfaceTopography topography, a HeightMap or a
    file, with its units explicit.

    Parameters
    ----------
    source : ndarray (ny, nx), SurfaceTopography topography, HeightMap or path
        A path ending .npy, .csv or .txt is read by :func:`read_height_map`; any other
        file (x3p, datx, opd, gwy, sur, ...) by SurfaceTopography
        (``pip install "./python[topography]"``), which records its units.
    pixel_size : float or (dx, dy)
        For arrays and plain files: in the unit of the heights.
    unit : str
        Length unit of the heights and pixel sizes ('m', 'mm', 'um', 'nm', ...);
        required for arrays and plain files (the map refuses to guess).
    height_unit : str, optional
        The heights' unit when it must be stated apart: refused unless equal to unit
        (heights in nm on pixels in um are a classic silent error).
    periodic : bool, optional
        Whether the map is periodic (default: SurfaceTopography's is_periodic, else
        False).

    Returns
    -------
    HeightMap

    Raises
    ------
    ValueError
        NaN pixels, heights that are not real numbers, a missing or unknown unit,
        mixed units, a bad pixel size or shape.
    ImportError
        An instrument format without SurfaceTopography installed.
    TypeError
        periodic neither None nor True or False ("no" would have meant True).
    """
    if periodic is not None:
        periodic = _flag("periodic", periodic)
    if height_unit is not None and height_unit != unit:
        raise ValueError(f"mixed units: heights in {_brief(height_unit)}, pixel size in "
                         f"{_brief(unit)}: give both in one unit (scale the heights by "
                         f"{_unit_factor(height_unit) / _unit_factor(unit):g})")
    if isinstance(source, HeightMap):
        if unit is not None and source.unit is not None and unit != source.unit:
            raise ValueError(f"mixed units: the map is in {_brief(source.unit)}, "
                             f"unit = {_brief(unit)}")
        return dataclasses.replace(source, unit=source.unit or unit,
                                   periodic=source.periodic if periodic is None
                                   else bool(periodic))
    if _is_surface_topography(source):
        return _from_surface_topography(source, unit, periodic)
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        if os.path.splitext(path)[1].lower() in (".npy", ".csv", ".txt", ".dat", ""):
            if unit is None:
                raise ValueError(f"{path}: a plain height map carries no unit: give unit= "
                                 "(CLI: --unit)")
            hm = read_height_map(path, 1.0 if pixel_size is None else pixel_size, unit,
                                 bool(periodic))
            if pixel_size is None:
                raise ValueError(f"{path}: give pixel_size (CLI: --pixel-size)")
            return hm
        try:
            import SurfaceTopography as st  # noqa: N813 (the package's own name)
        except ImportError:
            raise ImportError(f"{path}: instrument formats are read by SurfaceTopography: "
                              "pip install './python[topography]' (from the egw "
                              "repository)") from None
        reader = st.open_topography(path)
        kwargs = {}
        if pixel_size is not None:
            dx, dy = (pixel_size, pixel_size) if np.isscalar(pixel_size) else pixel_size
            nx, ny = reader.channels[0].nb_grid_pts
            kwargs["physical_sizes"] = (dx * nx, dy * ny)
        if unit is not None and reader.channels[0].unit is None:
            kwargs["unit"] = unit
        return _from_surface_topography(reader.topography(**kwargs), unit, periodic)
    if unit is None:
        raise ValueError("a height array carries no unit: give unit= (the length unit of "
                         "the heights and pixel sizes)")
    return _checked_map(source, pixel_size, unit, bool(periodic), "the height array")


def coarse_grain(surface: HeightMap, factor: int = 2) -> HeightMap:
    """The map with pixels factor times larger: the means of factor x factor blocks (a
    low-pass at the new pixel; a row or column that fills no block is dropped).

    Parameters
    ----------
    surface : HeightMap
        The map.
    factor : int
        Block size, >= 1.

    Returns
    -------
    HeightMap
        Pixel sizes factor * (dx, dy); the same unit and periodicity.

    Raises
    ------
    ValueError
        A factor that is not a whole number or < 1, or a map with fewer than 3 x 3 blocks.
    """
    # a whole number only: int() would truncate 2.7 to 2 without a word
    if isinstance(factor, (bool, np.bool_)) or not isinstance(
            factor, (int, float, np.integer, np.floating)) or not (
            math.isfinite(factor) and factor == int(factor)):
        raise ValueError(f"factor = {_brief(factor)}: must be a whole number")
    factor = int(factor)
    ny, nx = surface.heights.shape
    if factor < 1 or ny // factor < 3 or nx // factor < 3:
        raise ValueError(f"factor = {factor}: must be >= 1 and leave at least 3 x 3 pixels "
                         f"of the {ny} x {nx} map")
    z = surface.heights[:ny - ny % factor, :nx - nx % factor]
    z = z.reshape(ny // factor, factor, nx // factor, factor).mean(axis=(1, 3))
    return HeightMap(z, surface.dx * factor, surface.dy * factor, surface.unit,
                     surface.periodic and ny % factor == 0 and nx % factor == 0)
