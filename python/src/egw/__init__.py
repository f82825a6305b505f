"""egw: extended Greenwood-Williamson contact of rough spheres (Zhao & Feng 2018), from
Python. A thin ctypes layer over the egw C library (include/egw.h): every number is
computed by the library; errors are raised as egw.EgwError subclasses carrying egw's
message (which names the offending parameter).

>>> import numpy as np, egw
>>> p = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)
>>> r = egw.solve(p, [0.0, 1e-6, 1e-5])       # full solves: r.force, r.stiffness, ...
>>> t = egw.Table.build(p, -2e-6, 2e-5, 1e-6)  # a force table for a DEM code
>>> force, stiffness = t.eval(np.linspace(0, 2e-5, 1000))
"""
from .errors import (EgwError, errstate, FileError, IgnoredParameterWarning, InvalidArgumentError,
                     last_error, NotConvergedError, OutOfRangeWarning, PointFailedWarning, version)
from .params import Options, Params
from .functions import (effective_modulus, ellipe, ellipk, flat_pressure, flat_pressure_unload,
                        gauss_integral, hertz, mu_from_summits)
from .solves import profile, solve, solve_unload, SolveResult
from .impact import first_yield, FirstYield, Restitution, restitution, time_step, TimeStep
from .scene import ModelChoice, Scene, build, choose
from .tables import HysteresisInfo, HysteresisTable, Table, TableInfo, UniversalTable
from .flat_law import FlatLaw
from .progress import set_progress
from .surface_choice import SurfaceChoice, choose_for_surface
from . import topography
from .topography import contact_from_topography, psi_from_hardness

__version__ = "0.3.6"

__all__ = ["EgwError", "FileError", "InvalidArgumentError", "NotConvergedError", "Options",
           "OutOfRangeWarning", "Params", "Restitution", "SolveResult", "ellipe", "ellipk",
           "flat_pressure", "flat_pressure_unload", "gauss_integral", "hertz", "last_error",
           "mu_from_summits", "profile", "restitution", "solve", "solve_unload", "version",
           "ModelChoice", "Scene", "build", "choose", "HysteresisInfo", "HysteresisTable", "Table",
           "TableInfo", "UniversalTable", "topography", "psi_from_hardness",
           "IgnoredParameterWarning", "PointFailedWarning", "TimeStep", "effective_modulus",
           "errstate", "time_step", "contact_from_topography", "FlatLaw", "FirstYield",
           "first_yield",
           "SurfaceChoice", "choose_for_surface", "set_progress"]
