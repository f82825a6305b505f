"""Scenes and the model choice: the cheapest model (Hertz, a 1-D table or the universal
table) that meets a scene's force tolerance (egw_scene_choose / egw_scene_build)."""
from __future__ import annotations

import ctypes
import os
from dataclasses import dataclass, field
from typing import List, Optional, Tuple, Union

from . import _capi
from ._capi import SCENE_MAX_TYPES, lib
from .core import MODELS, InvalidArgumentError, INVALID_PARAMETER, Options, _options, check
from .tables import Table, UniversalTable

CHOICES = {0: "Hertz", 1: "table", 2: "universal"}


@dataclass
class Scene:
    """A contact scene (fields of the C struct egw_scene, lists for the per-type arrays;
    defaults: egw-table's default scene, two 1 mm glass beads, sigma = 1 um, mu = 4)."""
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
        """The library's default scene (egw_scene_default)."""
        c = _capi.Scene()
        lib.egw_scene_default(ctypes.byref(c))
        return cls.from_c(c)

    @classmethod
    def read(cls, path: Union[str, os.PathLike], base: Optional["Scene"] = None) -> "Scene":
        """Read the namelist group &scene of a file over `base` (default scene)."""
        c = (base or cls.default()).to_c()
        check(lib.egw_scene_read(os.fsencode(path), ctypes.byref(c)))
        return cls.from_c(c)

    @classmethod
    def from_c(cls, c: _capi.Scene) -> "Scene":
        """The Scene of a C struct egw_scene."""
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
        """The C struct egw_scene (InvalidArgumentError for an unknown model or more than
        SCENE_MAX_TYPES particle types)."""
        model = MODELS.get(self.model, self.model) if isinstance(self.model, str) else self.model
        if isinstance(model, str):
            raise InvalidArgumentError(INVALID_PARAMETER,
                                       f"model = {model!r}: must be one of {list(MODELS)}")
        for name in ("radius", "modulus", "poisson"):
            if len(getattr(self, name)) > SCENE_MAX_TYPES:
                raise InvalidArgumentError(
                    INVALID_PARAMETER, f"{name}: at most {SCENE_MAX_TYPES} particle types")
        c = _capi.Scene()
        c.model = int(model)
        c.n_types = len(self.radius)
        for name in ("radius", "modulus", "poisson"):
            arr = getattr(c, name)
            for i, v in enumerate(getattr(self, name)):
                arr[i] = float(v)
        for name in ("radius_min", "radius_max", "effective_modulus", "sigma_min",
                     "sigma_max", "mu", "summit_density", "summit_radius", "psi",
                     "hardness_coeff", "plastic_ratio", "delta_min", "delta_max", "tol"):
            setattr(c, name, float(getattr(self, name)))
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
    """The chosen model (kind: 'Hertz', 'table' or 'universal'), why, and its error."""
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
        """The ModelChoice of a C struct egw_model_choice and its reason text."""
        return cls(CHOICES.get(c.kind, str(c.kind)), reason, c.n_sets, c.n_solves, c.n_nodes,
                   c.error_bound, c.hertz_error, c.measured_error, (c.mu_min, c.mu_max),
                   (c.x_min, c.x_max))


def choose(scene: Scene, options: Optional[Options] = None) -> ModelChoice:
    """The cheapest model meeting scene.tol (full solves for the Hertz check only)."""
    c = _capi.ModelChoice()
    reason = ctypes.create_string_buffer(512)
    check(lib.egw_scene_choose(ctypes.byref(scene.to_c()), _options(options),
                               ctypes.byref(c), reason, len(reason)))
    return ModelChoice.from_c(c, reason.value.decode())


def build(scene: Scene, options: Optional[Options] = None
          ) -> Tuple[ModelChoice, Optional[Table], Optional[UniversalTable]]:
    """Choose, then build the chosen table: (choice, 1-D table or None, universal or None)."""
    c = _capi.ModelChoice()
    t, u = ctypes.c_void_p(), ctypes.c_void_p()
    check(lib.egw_scene_build(ctypes.byref(scene.to_c()), _options(options), ctypes.byref(c),
                              ctypes.byref(t), ctypes.byref(u)))
    choice = ModelChoice.from_c(c, "")
    return (choice, Table(t) if t.value else None, UniversalTable(u) if u.value else None)


__all__ = ["Scene", "ModelChoice", "choose", "build"]
