"""Array calls (one C call each, egw.h "Array kernels"): numpy broadcasting over overlaps
and parameters, values equal to the scalar calls bit for bit, NaN refused with the index
(or NaN with a count under egw.errstate), parameters checked at construction."""
import math
import subprocess
import sys
import warnings

import numpy as np
import pytest

import egw

ROUGH = dict(radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)


def _scalar(fn, *args):
    """fn over every element of the broadcast args, one scalar call each."""
    arrays = np.broadcast_arrays(*[np.asarray(a, dtype=float) for a in args])
    return [fn(*[float(a[idx]) for a in arrays]) for idx in np.ndindex(arrays[0].shape)]


def test_hertz_broadcasts_over_delta_and_params_bit_for_bit():
    radius = np.array([[1e-4], [5e-4], [2e-3]])       # (3, 1)
    modulus = np.array([1e9, 7e10])                   # (2,) -> (3, 2) with radius
    delta = np.array([[[-1e-6]], [[0.0]], [[1e-7]], [[3e-6]]])   # (4, 1, 1)
    p = egw.Params(model="Hertz", radius=radius, modulus=modulus)
    f, k, a = egw.hertz(p, delta)
    assert f.shape == k.shape == a.shape == (4, 3, 2)
    for idx in np.ndindex(f.shape):
        q = egw.Params(model="Hertz", radius=float(radius[idx[1], 0]),
                       modulus=float(modulus[idx[2]]))
        assert egw.hertz(q, float(delta[idx[0], 0, 0])) == (f[idx], k[idx], a[idx])


def test_flat_pressure_and_unload_broadcast_bit_for_bit():
    p = egw.Params(model="EP-GW", psi=np.array([0.5, 2.0]), **ROUGH)
    d = np.linspace(-3e-6, 2e-6, 5)[:, None]
    pr, dp = egw.flat_pressure(p, d, derivative=True)
    assert pr.shape == dp.shape == (5, 2)
    pu = egw.flat_pressure_unload(p, d, -2e-6)
    for i, j in np.ndindex(pr.shape):
        q = p.replace(psi=float(p.psi[j]))
        assert egw.flat_pressure(q, float(d[i, 0]), derivative=True) == (pr[i, j], dp[i, j])
        assert egw.flat_pressure_unload(q, float(d[i, 0]), -2e-6) == pu[i, j]


def test_gauss_integral_broadcasts_order_and_limit():
    n = np.array([0.0, 1.0, 1.5])[:, None]
    h = np.linspace(-2, 4, 4)
    got = egw.gauss_integral(n, h)
    assert got.shape == (3, 4)
    assert got.ravel().tolist() == _scalar(lambda a, b: egw.gauss_integral(a, b), n, h)


def test_solves_over_arrays_of_params_equal_scalar_solves_any_threads():
    p = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6,
                   mu=np.array([2.0, 4.0, 8.0]))
    delta = np.array([[-1e-6], [2e-6]])
    one = egw.solve(p, delta, egw.Options(n_threads=1))
    two = egw.solve(p, delta, egw.Options(n_threads=2))
    assert one.force.shape == (2, 3) and one.iterations.dtype == np.int32
    for idx in np.ndindex(one.force.shape):
        s = egw.solve(p.replace(mu=float(p.mu[idx[1]])), float(delta[idx[0], 0]),
                      egw.Options(n_threads=1))
        assert (s.force, s.stiffness) == (one.force[idx], one.stiffness[idx])
        assert (s.force, s.stiffness) == (two.force[idx], two.stiffness[idx])


def test_restitution_and_time_step_arrays():
    p = egw.Params(model="EP-GW", psi=2.0, **ROUGH)
    v = np.array([0.05, 0.5])
    r = egw.restitution(p, mass=1e-3, velocity=v)
    t = egw.time_step(p, mass=1e-3, velocity=v, tolerance=1e-3)
    for i in range(2):
        s = egw.restitution(p, mass=1e-3, velocity=float(v[i]))
        assert (s.e, s.work_load, s.dissipated, s.max_overlap) == (
            r.e[i], r.work_load[i], r.dissipated[i], r.max_overlap[i])
        assert s.max_overlap > 0 and 0 < s.e < 1
        ts = egw.time_step(p, mass=1e-3, velocity=float(v[i]), tolerance=1e-3)
        assert (ts.duration, ts.step) == (t.duration[i], t.step[i])
        assert 0 < ts.step < ts.duration
    # the faster impact is shorter and needs the smaller step (Hertz-like stiffening)
    assert t.step[1] < t.step[0]


def test_nan_raises_naming_the_index_or_gives_nan_under_errstate():
    p = egw.Params(model="Hertz")
    d = np.array([[1e-3, 2e-3], [float("nan"), 1e-3]])
    with pytest.raises(egw.InvalidArgumentError, match=r"index \(1, 0\): delta = NaN"):
        egw.hertz(p, d)
    with egw.errstate(failed="nan"):
        f, _, _ = egw.hertz(p, d)
    assert np.isnan(f[1, 0]) and np.isfinite(f[0]).all()
    with egw.errstate(failed="warn"), pytest.warns(egw.PointFailedWarning, match="1 of 4"):
        egw.hertz(p, d)
    pr = egw.Params(model="E-GW", **ROUGH)
    with pytest.raises(egw.InvalidArgumentError, match=r"index 1"):
        egw.solve(pr, [1e-6, float("nan")])
    with egw.errstate(failed="nan"):
        r = egw.solve(pr, [1e-6, float("nan")])
    assert np.isnan(r.force[1]) and r.iterations[1] == -1 and r.force[0] > 0
    with pytest.raises(ValueError, match="failed"):
        with egw.errstate(failed="ignore"):
            pass


def test_params_checked_at_construction():
    with pytest.raises(egw.InvalidArgumentError, match="model"):
        egw.Params(model="EGW")
    with pytest.raises(TypeError, match="radius"):
        egw.Params(radius="1e-3")
    with pytest.raises(TypeError, match="model"):
        egw.Params(model=None)
    with pytest.raises(TypeError, match="sigma"):
        egw.Params(sigma=True)
    for bad in (dict(radius=-1.0), dict(modulus=float("inf")), dict(sigma=float("nan")),
                dict(hardness_coeff=1.5), dict(plastic_ratio=1.0),
                dict(radius=np.array([1.0, -2.0]))):
        name = next(iter(bad))
        with pytest.raises(egw.InvalidArgumentError, match=name):
            egw.Params(**bad)
    with pytest.raises(egw.InvalidArgumentError, match="mu"):  # the library's range check
        egw.Params(sigma=1e-3, mu=1e30)
    with pytest.warns(egw.IgnoredParameterWarning, match="psi"):
        egw.Params(model="E-GW", psi=2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        egw.Params(model="EP-GW", psi=2.0)
    with pytest.raises(egw.InvalidArgumentError, match="broadcast"):
        egw.Params(radius=[1.0, 2.0], modulus=[1.0, 2.0, 3.0])
    # the fields are read-only arrays or floats; replace re-checks
    p = egw.Params(radius=[1.0, 2.0])
    assert p.shape == (2,) and not p.radius.flags.writeable
    with pytest.raises(egw.InvalidArgumentError):
        p.replace(modulus=-1.0)
    assert egw.Params(model=2) == egw.Params(model="E-GW")


def test_wrong_inputs_raise_named_errors():
    p = egw.Params(model="E-GW", **ROUGH)
    with pytest.raises(TypeError, match="delta"):
        egw.solve(p, None)
    with pytest.raises(TypeError, match="delta"):
        egw.hertz(p, "1e-6")
    with pytest.raises(TypeError, match="params"):
        egw.solve({"radius": 1.0}, 1e-6)
    with pytest.raises(ValueError, match="broadcast"):
        egw.flat_pressure_unload(p, [1.0, 2.0], [1.0, 2.0, 3.0])
    with pytest.raises(egw.InvalidArgumentError, match="mass"):
        egw.restitution(p, mass=[1e-3, -1.0], velocity=0.1)


def test_effective_modulus_and_mu_from_summits_arrays():
    assert egw.effective_modulus(70e9, 0.22) == pytest.approx(70e9 / (2 * (1 - 0.22 ** 2)))
    e = egw.effective_modulus(np.array([70e9, 210e9]), 0.3, 210e9, 0.3)
    assert e.shape == (2,)
    with pytest.raises(egw.InvalidArgumentError, match="nu1"):
        egw.effective_modulus(70e9, 0.7)
    mu = egw.mu_from_summits(summit_density=np.array([1e10, 2e10]), summit_radius=1e-5,
                             sigma=1e-6, radius=5e-4)
    assert mu.shape == (2,) and mu[1] == pytest.approx(2 * mu[0], rel=1e-15)


def _public_objects():
    names = [(n, getattr(egw, n)) for n in egw.__all__]
    names += [(f"topography.{n}", v) for n, v in vars(egw.topography).items()
              if not n.startswith("_") and callable(v)
              and (getattr(v, "__module__", None) or "").startswith(("egw.topography",
                                                                      "egw.topo_"))]
    for name, obj in names:
        yield name, obj
        if isinstance(obj, type):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if isinstance(member, (classmethod, staticmethod)):
                    member = member.__func__
                if callable(member) or isinstance(member, property):
                    yield f"{name}.{attr}", member


def test_every_public_name_has_a_docstring():
    missing = [name for name, obj in _public_objects()
               if not (getattr(obj, "__doc__", None) or "").strip()
               and not isinstance(obj, (int, float, str, dict))]
    assert not missing, f"no docstring: {missing}"


def test_python_m_egw_version():
    out = subprocess.run([sys.executable, "-m", "egw", "--version"], check=True,
                         capture_output=True, text=True).stdout
    assert out.startswith(f"egw {egw.__version__} (libegw {egw.version()}")
