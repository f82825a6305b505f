"""Scenes and the model choice: the cheapest model (Hertz, a 1-D table or the universal
table) that meets a scene's force tolerance (egw_scene_choose / egw_scene_build)."""
from __future__ import annotations

import ctypes
import os
from dataclasses import dataclass, field
from typing import List, Optional, Tuple, Union

from . import _capi
from ._capi import SCENE_MAX_TYPES, lib
from .errors import check, INVALID_PARAMETER, InvalidArgumentError, _brief
from .params import MODELS, Options, _c_scalar, _options
from .tables import Table, UniversalTable

CHOICES = {0: "Hertz", 1: "table", 2: "universal"}


@dataclass
class Scene:
    """A contact scene (fields of the C struct egw_scene, lists for the per-type arrays;
    defaults: egw-table's default scene, two 1 mm glass beads, sigma = 1 um, mu = 4).
    doc/scenes.md describes scenes and the choice rule. Units: any consistent set. There
    is no flow_pressure (nor yield_stress): egw_scene has none (an ABI change); a pair
    with the bulk cap takes ``HysteresisTable.build(Params(..., flow_pressure=p_y), ...)``,
    or egw-table's ``--flow-pressure``/``--yield-stress``.

    Parameters
    ----------
    model : str or int
        'Hertz', 'GW', 'E-GW' or 'EP-GW' (or 0..3).
    radius : list of float
        Particle radius of each type (1..8 types) [length]; empty: the radius range.
    radius_min, radius_max : float
        Radius range of one material when radius is empty [length].
    modulus, poisson : list of float
        Young's modulus [pressure] and Poisson's ratio per type (a type >= 2 with modulus
        0 has type 1's material).
    effective_modulus : float
        E* of every pair if > 0 (modulus and poisson are then unused) [pressure].
    sigma_min, sigma_max : float
        Combined summit-height std of a pair [length]; equal: one value; both 0: smooth.
    mu : float
        Greenwood-Tripp mu if > 0; else from summit_density and summit_radius per pair.
    summit_density, summit_radius : float
        eta [1/length^2] and beta [length] when mu = 0.
    psi, hardness_coeff, plastic_ratio : float
        EP-GW: psi >= 0, K in (0, 1), rho_p > 1.
    delta_min, delta_max : float
        Overlap range (< 0: separation), in units of sigma when delta_in_sigma.
    delta_in_sigma : bool
        delta_min, delta_max in units of sigma (True) or of length (False).
    tol : float
        Relative force tolerance of the model choice, 1e-8 .. 0.1.
    """
    model: Union[str, int] = "E-GW"
    radius: List[float] = field(default_factory=lambda: [1.0e-3])
    radius_min: float = 0.0
    radius_max: float = 0.0
    modulus: List[float] = field(default_factory=lambda: [70.0e9])
    poisson: List[float] = field(default_factory=lambda: [0.22])
    effective_modulus: float = 0.0
    sigma_min: float = 1.0e-6
    sigma_max: float = 1.0e-6
    mu: float = 4.0
    summit_density: float = 0.0
    summit_radius: float = 0.0
    psi: float = 0.0
    hardness_coeff: float = 0.6
    plastic_ratio: float = 54.0
    delta_min: float = -2.0
    delta_max: float = 20.0
    delta_in_sigma: bool = True
    tol: float = 1e-4

    @classmethod
    def default(cls) -> "Scene":
        """The library's default scene (egw_scene_default).

        Returns
        -------
        Scene
            Two 1 mm glass beads (E = 70 GPa, nu = 0.22), sigma = 1 um, mu = 4, E-GW,
            overlaps -2 .. 20 sigma, tol = 1e-4.
        """
        c = _capi.Scene()
        lib.egw_scene_default(ctypes.byref(c))
        return cls.from_c(c)

    @classmethod
    def read(cls, path: Union[str, os.PathLike], base: Optional["Scene"] = None) -> "Scene":
        """Read the namelist group &scene of a file (egw_scene_read).

        Parameters
        ----------
        path : str or os.PathLike
            The file (variables in doc/scenes.md).
        base : Scene, optional
            The values the file does not give (default: :meth:`default`).

        Returns
        -------
        Scene
            base with the file's values, validated.

        Raises
        ------
        FileError
            The file cannot be read, has no &scene, an unknown variable or an unreadable
            value (the message says which).
        InvalidArgumentError
            A value out of range.
        """
        c = (base or cls.default()).to_c()
        check(lib.egw_scene_read(os.fsencode(path), ctypes.byref(c)))
        return cls.from_c(c)

    @classmethod
    def from_c(cls, c: _capi.Scene) -> "Scene":
        """The Scene of a C struct egw_scene.

        Parameters
        ----------
        c : egw._capi.Scene
            The C struct.

        Returns
        -------
        Scene
        """
        n = c.n_types
        model = {v: k for k, v in MODELS.items()}.get(c.model, c.model)
        return cls(model=model, radius=list(c.radius[:n]), radius_min=c.radius_min,
                   radius_max=c.radius_max, modulus=list(c.modulus[:max(n, 1)]),
                   poisson=list(c.poisson[:max(n, 1)]),
                   effective_modulus=c.effective_modulus, sigma_min=c.sigma_min,
                   sigma_max=c.sigma_max, mu=c.mu, summit_density=c.summit_density,
                   summit_radius=c.summit_radius, psi=c.psi, hardness_coeff=c.hardness_coeff,
                   plastic_ratio=c.plastic_ratio, delta_min=c.delta_min,
                   delta_max=c.delta_max, delta_in_sigma=bool(c.delta_in_sigma), tol=c.tol)

    def to_c(self) -> _capi.Scene:
        """The C struct egw_scene of this scene.

        Returns
        -------
        egw._capi.Scene

        Raises
        ------
        InvalidArgumentError
            An unknown model, more than SCENE_MAX_TYPES particle types, or (without
            effective_modulus) modulus and poisson lists of different lengths or
            longer than radius.
        TypeError
            radius, modulus or poisson not a list (one value per type); a field that is
            not a real number, a model number that is not a whole number, delta_in_sigma
            not a bool (each named).
        """
        model = MODELS.get(self.model, self.model) if isinstance(self.model, str) else self.model
        if isinstance(model, str):
            raise InvalidArgumentError(INVALID_PARAMETER,
                                       f"model = {_brief(model)}: must be one of {list(MODELS)}")
        for name in ("radius", "modulus", "poisson"):
            value = getattr(self, name)
            if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
                raise TypeError(f"{name} = {_brief(value)}: must be a list of floats, one per "
                                f"particle type (e.g. {name}=[{_brief(value)}])")
            if len(value) > SCENE_MAX_TYPES:
                raise InvalidArgumentError(
                    INVALID_PARAMETER, f"{name}: at most {SCENE_MAX_TYPES} particle types")
        # E and nu per type are used (no effective_modulus): the C struct's zeros would give
        # a type whose poisson was left out nu = 0, and values beyond the types go unused
        n_types = max(1, len(self.radius))
        if not _c_scalar("effective_modulus", self.effective_modulus) > 0 and (
                len(self.modulus) != len(self.poisson) or len(self.modulus) > n_types):
            raise InvalidArgumentError(
                INVALID_PARAMETER, f"modulus, poisson: {len(self.modulus)} and "
                f"{len(self.poisson)} values for {n_types} particle type(s): give both for "
                "each type (a type >= 2 left out of both has type 1's material)")
        c = _capi.Scene()
        c.model = _c_scalar("model", model, True)
        c.n_types = len(self.radius)
        for name in ("radius", "modulus", "poisson"):
            arr = getattr(c, name)
            for i, v in enumerate(getattr(self, name)):
                arr[i] = _c_scalar(f"{name}[{i}]", v, False)
        for name in ("radius_min", "radius_max", "effective_modulus", "sigma_min",
                     "sigma_max", "mu", "summit_density", "summit_radius", "psi",
                     "hardness_coeff", "plastic_ratio", "delta_min", "delta_max", "tol"):
            setattr(c, name, _c_scalar(name, getattr(self, name), False))
        if self.delta_in_sigma not in (True, False):   # 0.5 was True (bool()), silently
            raise TypeError(f"delta_in_sigma = {_brief(self.delta_in_sigma)}: must be True or "
                            "False (overlaps in units of sigma, or in length)")
        c.delta_in_sigma = int(bool(self.delta_in_sigma))
        return c

    def validate(self) -> None:
        """Check the scene with the library (egw_scene_validate).

        Raises
        ------
        InvalidArgumentError
            Naming the first invalid field.
        """
        check(lib.egw_scene_validate(ctypes.byref(self.to_c())))


@dataclass
class ModelChoice:
    """The chosen model, why, and its error (the C struct egw_model_choice).

    Attributes
    ----------
    kind : str
        'Hertz', 'table' (one 1-D table) or 'universal' (the 2-D table).
    reason : str
        Why (egw_scene_choose's text; empty after :func:`build`).
    n_sets : int
        Distinct pair parameter sets of the scene.
    n_solves : int
        Full solves spent on the Hertz check.
    n_nodes : int
        Table nodes (universal: x nodes times mu nodes); :func:`build` only.
    error_bound : float
        Hertz: its measured error; tables: the tolerance they are built to.
    hertz_error : float
        The Hertz error measure (0 for smooth spheres).
    measured_error : float
        Max relative force error at the build's check solves (:func:`build` only).
    mu_range : (float, float)
        mu range of the pairs.
    x_range : (float, float)
        delta/sigma range of the pairs (0 if smooth).
    """
    kind: str
    reason: str
    n_sets: int
    n_solves: int
    n_nodes: int
    error_bound: float
    hertz_error: float
    measured_error: float
    mu_range: Tuple[float, float]
    x_range: Tuple[float, float]

    @classmethod
    def from_c(cls, c: _capi.ModelChoice, reason: str) -> "ModelChoice":
        """The ModelChoice of a C struct egw_model_choice.

        Parameters
        ----------
        c : egw._capi.ModelChoice
            The C struct.
        reason : str
            Its reason text.

        Returns
        -------
        ModelChoice
        """
        return cls(CHOICES.get(c.kind, str(c.kind)), reason, c.n_sets, c.n_solves, c.n_nodes,
                   c.error_bound, c.hertz_error, c.measured_error, (c.mu_min, c.mu_max),
                   (c.x_min, c.x_max))


def choose(scene: Scene, options: Optional[Options] = None) -> ModelChoice:
    """The cheapest model meeting scene.tol (egw_scene_choose; full solves for the Hertz
    check only, no table built).

    Parameters
    ----------
    scene : Scene
        The scene.
    options : Options, optional
        Solver options of the Hertz check.

    Returns
    -------
    ModelChoice
        kind, reason and error measures.

    Raises
    ------
    InvalidArgumentError
        An invalid scene (the field named).
    NotConvergedError
        A solve of the Hertz check failed.
    """
    c = _capi.ModelChoice()
    reason = ctypes.create_string_buffer(512)
    check(lib.egw_scene_choose(ctypes.byref(scene.to_c()), _options(options),
                               ctypes.byref(c), reason, len(reason)))
    return ModelChoice.from_c(c, reason.value.decode())


def build(scene: Scene, options: Optional[Options] = None
          ) -> Tuple[ModelChoice, Optional[Table], Optional[UniversalTable]]:
    """Choose the model, then build the chosen table (egw_scene_build).

    Parameters
    ----------
    scene : Scene
        The scene.
    options : Options, optional
        Solver options of the check and the build.

    Returns
    -------
    choice : ModelChoice
        As :func:`choose`, with n_nodes and measured_error.
    table : Table or None
        The 1-D table when choice.kind is 'table'.
    universal : UniversalTable or None
        The universal table when choice.kind is 'universal'.

    Raises
    ------
    InvalidArgumentError
        An invalid scene.
    NotConvergedError
        A solve failed.
    """
    c = _capi.ModelChoice()
    t, u = ctypes.c_void_p(), ctypes.c_void_p()
    check(lib.egw_scene_build(ctypes.byref(scene.to_c()), _options(options), ctypes.byref(c),
                              ctypes.byref(t), ctypes.byref(u)))
    choice = ModelChoice.from_c(c, "")
    return (choice, Table(t) if t.value else None, UniversalTable(u) if u.value else None)


__all__ = ["Scene", "ModelChoice", "choose", "build"]
