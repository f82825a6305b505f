"""ctypes declarations of the egw C API (include/egw.h). Private: use the `egw` package.

Each structure mirrors its C struct field for field; tests/test_capi_layout.py checks the
sizes against the header. Functions added to the C API later are declared when the loaded
library has them (`has(name)`), so the package also runs on an older libegw.
"""
from __future__ import annotations

import ctypes
import ctypes.util
import os
from ctypes import CFUNCTYPE, POINTER, c_char_p, c_double, c_int, c_void_p

__all__ = ["lib", "has", "Params", "Options", "Result", "TableInfo", "Scene",
           "ModelChoice", "SCENE_MAX_TYPES", "PROGRESS_FN"]

SCENE_MAX_TYPES = 8


def _load() -> ctypes.CDLL:
    candidates = []
    if os.environ.get("EGW_LIBRARY"):
        candidates.append(os.environ["EGW_LIBRARY"])
    candidates.append(os.path.join(os.path.dirname(__file__), "_lib", "libegw.so"))
    found = ctypes.util.find_library("egw")
    if found:
        candidates.append(found)
    errors = []
    for path in candidates:
        if os.path.sep in path and not os.path.exists(path):
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as exc:  # keep going: report every place tried
            errors.append(f"{path}: {exc}")
    raise ImportError("egw: cannot load libegw (tried: " + "; ".join(errors or candidates)
                      + "). Install the package with `pip install ./python` from the egw "
                      "repository, or set EGW_LIBRARY to libegw.so")


lib = _load()


class Params(ctypes.Structure):
    _fields_ = [("model", c_int), ("radius", c_double), ("modulus", c_double),
                ("sigma", c_double), ("mu", c_double), ("psi", c_double),
                ("hardness_coeff", c_double), ("plastic_ratio", c_double),
                ("flow_pressure", c_double)]


class Options(ctypes.Structure):
    _fields_ = [("n_radial", c_int), ("rel_tol", c_double), ("max_iter", c_int),
                ("method", c_int), ("n_threads", c_int)]


class Result(ctypes.Structure):
    _fields_ = [("force", c_double), ("stiffness", c_double), ("contact_radius", c_double),
                ("max_pressure", c_double), ("est_rel_err", c_double),
                ("residual", c_double), ("iterations", c_int), ("method_used", c_int)]


class TableInfo(ctypes.Structure):
    _fields_ = [("model", c_int), ("n_nodes", c_int), ("cutoff", c_double),
                ("delta_max", c_double), ("reference_force", c_double),
                ("rel_tol", c_double), ("max_force_error", c_double),
                ("max_stiffness_error", c_double), ("checksum_missing", c_int)]


_TYPES = c_double * SCENE_MAX_TYPES


class HysteresisInfo(ctypes.Structure):
    _fields_ = [("model", c_int), ("reversible", c_int), ("n_delta_max", c_int),
                ("n_s", c_int), ("n_loading", c_int), ("cutoff", c_double),
                ("delta_max", c_double), ("reference_force", c_double),
                ("rel_tol", c_double), ("max_error", c_double), ("params", Params)]


class Scene(ctypes.Structure):
    _fields_ = [("model", c_int), ("n_types", c_int), ("radius", _TYPES),
                ("radius_min", c_double), ("radius_max", c_double), ("modulus", _TYPES),
                ("poisson", _TYPES), ("effective_modulus", c_double),
                ("sigma_min", c_double), ("sigma_max", c_double), ("mu", c_double),
                ("summit_density", c_double), ("summit_radius", c_double),
                ("psi", c_double), ("hardness_coeff", c_double),
                ("plastic_ratio", c_double), ("delta_min", c_double),
                ("delta_max", c_double), ("delta_in_sigma", c_int), ("tol", c_double)]


class ModelChoice(ctypes.Structure):
    _fields_ = [("kind", c_int), ("n_sets", c_int), ("n_solves", c_int),
                ("hertz_relative_to_max", c_int), ("n_nodes", c_int),
                ("error_bound", c_double), ("hertz_error", c_double),
                ("measured_error", c_double), ("mu_min", c_double), ("mu_max", c_double),
                ("x_min", c_double), ("x_max", c_double)]


_dp = POINTER(c_double)
# egw_progress_fn: void (*)(double done, const char *stage, void *user)
PROGRESS_FN = CFUNCTYPE(None, c_double, c_char_p, c_void_p)
_ip = POINTER(c_int)
_P, _O = POINTER(Params), POINTER(Options)

# name: (restype, argtypes)
_SIGNATURES = {
    "egw_get_version": (c_int, []),
    "egw_status_message": (c_int, [c_int, c_char_p, c_int]),
    "egw_last_error": (c_int, [c_char_p, c_int]),
    "egw_set_progress": (None, [PROGRESS_FN, c_void_p]),
    "egw_params_default": (None, [_P]),
    "egw_params_validate": (c_int, [_P]),
    "egw_mu_from_summits": (c_int, [c_double, c_double, c_double, c_double, _dp]),
    "egw_psi_from_hardness": (c_int, [c_double, c_double, c_double, c_double, c_double,
                                      _dp]),
    "egw_gauss_integral": (c_int, [c_double, c_double, _dp]),
    "egw_gauss_integral_deriv": (c_int, [c_double, c_double, _dp]),
    "egw_ellipk": (c_int, [c_double, _dp]),
    "egw_ellipe": (c_int, [c_double, _dp]),
    "egw_flat_pressure": (c_int, [_P, c_double, _dp]),
    "egw_flat_pressure_deriv": (c_int, [_P, c_double, _dp, _dp]),
    "egw_flat_pressure_unload": (c_int, [_P, c_double, c_double, _dp, _dp]),
    "egw_hertz": (c_int, [_P, c_double, _dp, _dp, _dp]),
    "egw_options_default": (None, [_O]),
    "egw_solve": (c_int, [_P, _O, c_double, POINTER(Result)]),
    "egw_solve_unload": (c_int, [_P, _O, c_double, c_double, POINTER(Result)]),
    "egw_restitution": (c_int, [_P, _O, c_double, c_double, _dp]),
    "egw_restitution_energy": (c_int, [_P, _O, c_double, c_double, _dp, _dp, _dp]),
    "egw_profile": (c_int, [_P, _O, c_double, c_int, _dp, _dp, _dp]),
    "egw_profile_unload": (c_int, [_P, _O, c_double, c_double, c_int, _dp, _dp, _dp]),
    "egw_table_build": (c_int, [_P, _O, c_double, c_double, c_double, POINTER(c_void_p)]),
    "egw_table_eval": (c_int, [c_void_p, c_double, _dp, _dp]),
    "egw_table_eval_array": (c_int, [c_void_p, c_int, _dp, _dp, _dp]),
    "egw_table_eval_all": (c_int, [c_void_p, c_double, _dp, _dp, _dp, _dp]),
    "egw_table_get_info": (c_int, [c_void_p, POINTER(TableInfo)]),
    "egw_table_write": (c_int, [c_void_p, c_char_p, c_int]),
    "egw_table_read": (c_int, [c_char_p, POINTER(c_void_p)]),
    "egw_table_free": (None, [POINTER(c_void_p)]),
    "egw_universal_build": (c_int, [_P, _O, c_double, c_double, c_double, c_double,
                                    c_double, POINTER(c_void_p)]),
    "egw_universal_eval": (c_int, [c_void_p, _P, c_double, _dp, _dp]),
    "egw_universal_slice": (c_int, [c_void_p, _P, POINTER(c_void_p)]),
    "egw_universal_slice_range": (c_int, [c_void_p, _P, c_double, POINTER(c_void_p)]),
    "egw_universal_write": (c_int, [c_void_p, c_char_p, c_int]),
    "egw_universal_read": (c_int, [c_char_p, POINTER(c_void_p)]),
    "egw_universal_free": (None, [POINTER(c_void_p)]),
    "egw_hysteresis_build": (c_int, [_P, _O, c_double, c_double, c_double,
                                     POINTER(c_void_p)]),
    "egw_hysteresis_eval": (c_int, [c_void_p, c_double, _dp, _dp, _dp]),
    "egw_hysteresis_eval_array": (c_int, [c_void_p, c_int, _dp, _dp, _dp, _dp]),
    "egw_hysteresis_energy": (c_int, [c_void_p, c_double, c_double, _dp]),
    "egw_hysteresis_get_info": (c_int, [c_void_p, POINTER(HysteresisInfo)]),
    "egw_hysteresis_write": (c_int, [c_void_p, c_char_p, c_int]),
    "egw_hysteresis_read": (c_int, [c_char_p, POINTER(c_void_p)]),
    "egw_hysteresis_free": (None, [POINTER(c_void_p)]),
    "egw_scene_default": (None, [POINTER(Scene)]),
    "egw_scene_validate": (c_int, [POINTER(Scene)]),
    "egw_scene_read": (c_int, [c_char_p, POINTER(Scene)]),
    "egw_scene_choose": (c_int, [POINTER(Scene), _O, POINTER(ModelChoice), c_char_p, c_int]),
    "egw_scene_build": (c_int, [POINTER(Scene), _O, POINTER(ModelChoice), POINTER(c_void_p),
                                POINTER(c_void_p)]),
    "egw_restitution_overlap": (c_int, [_P, _O, c_double, c_double, _dp, _dp]),
    "egw_time_step": (c_int, [_P, _O, c_double, c_double, c_double, _dp, _dp]),
    "egw_first_yield": (c_int, [_P, c_double, _dp, _dp]),
    # array kernels (egw.h "Array kernels"): a stride after every input
    "egw_hertz_array": (c_int, [_P, c_int, c_int, _dp, c_int, _dp, _dp, _dp, c_int, _ip]),
    "egw_flat_pressure_array": (c_int, [_P, c_int, c_int, _dp, c_int, _dp, _dp, c_int, _ip]),
    "egw_flat_pressure_unload_array": (c_int, [_P, c_int, c_int, _dp, c_int, _dp, c_int, _dp,
                                               _dp, c_int, _ip]),
    "egw_gauss_integral_array": (c_int, [c_int, _dp, c_int, _dp, c_int, _dp, _dp, c_int,
                                         _ip]),
    "egw_solve_array": (c_int, [_P, c_int, _O, c_int, _dp, c_int, _dp, c_int,
                                POINTER(Result), c_int, _ip]),
    "egw_restitution_array": (c_int, [_P, c_int, _O, c_int, _dp, c_int, _dp, c_int, _dp, _dp,
                                      _dp, _dp, c_int, _ip]),
    "egw_universal_eval_array": (c_int, [c_void_p, _P, c_int, c_int, _dp, c_int, _dp, _dp,
                                         c_int, _ip]),
    "egw_time_step_array": (c_int, [_P, c_int, _O, c_int, _dp, c_int, _dp, c_int, c_double,
                                    _dp, _dp, c_int, _ip]),
    # rough-flat laws (egw.h "Rough-flat laws beyond GW")
    "egw_flat_law_from_table": (c_int, [_dp, _dp, _dp, _dp, c_int, c_double, c_double,
                                        POINTER(c_void_p)]),
    "egw_flat_law_pressure": (c_int, [c_void_p, c_double, _dp, _dp]),
    "egw_flat_law_contact_area": (c_int, [c_void_p, c_double, _dp]),
    "egw_flat_law_info": (c_int, [c_void_p, _ip, _dp, _dp, _dp, _dp, _ip]),
    "egw_flat_law_free": (None, [POINTER(c_void_p)]),
    "egw_flat_law_write": (c_int, [c_void_p, c_char_p]),
    "egw_flat_law_from_psd": (c_int, [_dp, _dp, c_int, c_double, c_double, c_double,
                                      POINTER(c_void_p)]),
    "egw_flat_law_from_heights": (c_int, [_dp, c_int, c_int, c_double, c_double, c_double,
                                          c_double, _O, POINTER(c_void_p)]),
    "egw_flat_law_read": (c_int, [c_char_p, POINTER(c_void_p)]),
    "egw_solve_flat_law": (c_int, [_P, c_void_p, _O, c_double, POINTER(Result)]),
    "egw_table_build_flat_law": (c_int, [_P, c_void_p, _O, c_double, c_double, c_double,
                                         POINTER(c_void_p)]),
}

for _name, (_res, _args) in _SIGNATURES.items():
    if hasattr(lib, _name):
        _fn = getattr(lib, _name)
        _fn.restype = _res
        _fn.argtypes = _args


def has(name: str) -> bool:
    """True if the loaded libegw exports the C function `name`."""
    return hasattr(lib, name)
