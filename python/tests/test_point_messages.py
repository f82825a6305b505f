"""What a user reads when a point or egw-topo fails (stop 60, road26: found by following
the READMEs from a fresh clone).

- A failing point's index is shown as README.md states it, ``index 1:`` or
  ``index (1, 0):``; the flat-law solve and Params validation printed numpy 2's
  ``(np.int64(1),)``.
- ``egw-topo --choose`` on a surface whose BEM-law sphere solve does not converge ended in
  a Python traceback (NotConvergedError is no ValueError): it prints one line and exits 2.
Exact string checks: no tolerance involved.
"""
import numpy as np
import pytest

import egw
import egw.surface_choice
from egw import topo_cli


def _law():
    # an exponential law p = exp(-u/1e-6) Pa over 0..10 um (a valid tabulated law)
    u = np.linspace(0.0, 1e-5, 21)
    return egw.FlatLaw.from_table(u, np.exp(-u / 1e-6))


def test_flat_law_solve_names_the_point_as_readme_does():
    p = egw.Params(radius=1e-3, modulus=1e9, flat_law=_law())
    with pytest.raises(egw.EgwError) as info:
        egw.solve(p, np.array([1e-7, np.nan]))
    assert str(info.value).startswith("index 1: "), str(info.value)
    with pytest.raises(egw.EgwError) as info:
        egw.solve(p, np.array([[1e-7, 1e-7], [np.nan, 1e-7]]))
    assert str(info.value).startswith("index (1, 0): "), str(info.value)


def test_params_validation_names_the_point_as_readme_does():
    # flow_pressure must lie below E*: the library's check, per point
    p = egw.Params(model="Hertz", radius=1e-3, modulus=1e9,
                   flow_pressure=np.array([1e8, 2e9]))
    with pytest.raises(egw.InvalidArgumentError) as info:
        p.validate()
    assert str(info.value).startswith("index 1: flow_pressure"), str(info.value)
    assert "np.int64" not in str(info.value)


def test_topo_choose_failure_is_one_line(tmp_path, monkeypatch, capsys):
    def not_converged(*args, **kwargs):
        raise egw.NotConvergedError(3, "delta = 5.0E-01 (in units of sigma): Newton did "
                                       "not converge in 100 iterations")
    monkeypatch.setattr(egw.surface_choice, "choose_for_surface", not_converged)
    heights = np.random.default_rng(1).normal(size=(32, 32))
    np.save(tmp_path / "s.npy", heights)
    status = topo_cli.main([str(tmp_path / "s.npy"), "--pixel-size", "0.5", "--unit", "um",
                            "--periodic", "--radius", "500", "--modulus", "3.678e10",
                            "--choose", "0.03"])
    err = capsys.readouterr().err
    assert status == 2
    assert err.startswith("egw-topo: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and "did not converge" in err
