"""egw's Persson and BEM rough-flat laws through the Python API: FlatLaw.from_heights
against ContactMechanics' periodic FFT system on the same 64^2 map (when installed),
FlatLaw.from_psd against its closed-form limits, and contact_from_topography with
model='BEM' | 'Persson' through egw.solve and Table.build."""
import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import egw

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "reference"))
from bem_contactmechanics import self_affine_map  # noqa: E402  (seeded map, numpy only)

HAVE_CM = importlib.util.find_spec("ContactMechanics") is not None
HAVE_ST = importlib.util.find_spec("SurfaceTopography") is not None


@pytest.mark.skipif(not (HAVE_CM and HAVE_ST), reason="ContactMechanics not installed")
def test_bem_law_against_contactmechanics():
    # the goal: mean separation within 1e-3 of the rms height, area within 1 %, at
    # each load; CM run here at tight tolerances (pentol 1e-9 rms)
    from bem_contactmechanics import solve_cm
    n = 64
    h = self_affine_map(n)
    rms = np.sqrt(np.mean(h ** 2))
    loads = [1e-4, 1e-3, 1e-2]
    rows, _ = solve_cm(h, loads)
    law = egw.FlatLaw.from_heights(h, 1.0 / n, 1.0, p_min=1e-4, p_max=1e-2)
    for p, u_cm, a_cm in rows:
        lo, hi = law.separation_range
        us = np.linspace(lo, hi, 20001)
        u = us[np.argmin(abs(np.log(law.pressure(us) / p)))]   # nodes include p exactly
        assert abs(u - u_cm) <= 1e-3 * rms, (p, u, u_cm)
        assert law.contact_area(u) == pytest.approx(a_cm, rel=0.01, abs=1e-4)


def test_bem_law_basics():
    n = 32
    h = self_affine_map(n)
    law = egw.FlatLaw.from_heights(h, 1.0 / n, 1.0)
    assert law.length == pytest.approx(np.sqrt(np.mean(h ** 2)), rel=1e-12)
    assert law.modulus == 1.0 and law.has_area
    u = np.linspace(*law.separation_range, 50)
    p, d = law.pressure(u, derivative=True)
    assert np.all(np.diff(p) < 0) and np.all(d < 0)
    a = law.contact_area(u)
    assert np.all(np.diff(a) <= 1e-15) and np.all((a >= 0) & (a <= 1))
    with pytest.raises(egw.InvalidArgumentError):
        egw.FlatLaw.from_heights(np.full((8, 8), np.nan), 1.0, 1.0)
    with pytest.raises(egw.InvalidArgumentError):
        egw.FlatLaw.from_heights(h, -1.0, 1.0)


def test_persson_small_load_area():
    # A/A0 -> sqrt(8/pi) p/(E* h'_rms) (Persson's small-load limit), with the spectrum's
    # h'_rms^2 = 2 pi int q^3 C dq in closed form for a single power law
    q = np.array([1e4, 1e6])
    C = 1e-24 * (q / q[0]) ** -3.6
    a = -3.6
    m2 = 2 * np.pi * 1e-24 * q[0] ** 4 * ((q[1] / q[0]) ** (4 + a) - 1) / (4 + a)
    law = egw.FlatLaw.from_psd(q, C, 1e9, p_min=1e-3, p_max=1e5)
    u_small = law.separation_range[1]          # the node at p_min
    assert law.contact_area(u_small) == pytest.approx(
        math.sqrt(8 / math.pi) * 1e-3 / (1e9 * math.sqrt(m2)), rel=1e-9)


@pytest.mark.skipif(not HAVE_ST, reason="SurfaceTopography not installed")
@pytest.mark.parametrize("model", ["BEM", "Persson"])
def test_contact_from_topography_flat_laws(model):
    from SurfaceTopography import Topography
    n = 64
    h = self_affine_map(n, rms=1e-7)
    top = Topography(h, physical_sizes=(1e-4, 1e-4), periodic=True, unit="m")
    p, report = egw.contact_from_topography(top, radius=1e-3, E1=1e9, nu1=0.3,
                                            model=model)
    assert p.model == "flat law" and report.y_s == 0.0
    assert p.flat_law.length == pytest.approx(1e-7, rel=1e-6)
    r = egw.solve(p, [0.0, 1e-7, 5e-7])
    assert np.all(np.diff(r.force) > 0) and np.all(r.est_rel_err < 1e-5)
    t = egw.Table.build(p, -2e-7, 5e-7, 1e-4)
    f, _ = t.eval(np.array([0.0, 1e-7, 5e-7]))
    np.testing.assert_allclose(f, r.force, rtol=2e-4)


def test_bem_refuses_non_periodic_map():
    h = self_affine_map(16, rms=1e-7)
    with pytest.raises(ValueError, match="not periodic"):
        egw.FlatLaw.from_topography(h, 1e9, "BEM", pixel_size=1e-6, unit="m")
