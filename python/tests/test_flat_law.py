"""egw.FlatLaw and Params(flat_law=...): tabulated rough-flat laws through the sphere solve
and the 1-D table, checked against closed forms of an exponential law."""
import math

import numpy as np
import pytest

import egw

L, P0, R, E = 1e-6, 1.0, 1e-2, 1e12


def exponential_law(**kw):
    u = np.array([0.0, 1e-6, 3e-6])
    return egw.FlatLaw.from_table(u, P0 * np.exp(-u / L), **kw)


def test_pressure_exact_for_an_exponential():
    # ln p linear: the Hermite pieces and both continuations are that line (1e-14)
    law = exponential_law(area=[0.5, 0.3, 0.1])
    u = np.linspace(-2e-6, 8e-6, 11).reshape(11, 1)
    p, d = law.pressure(u, derivative=True)
    assert p.shape == (11, 1)
    np.testing.assert_allclose(p, P0 * np.exp(-u / L), rtol=1e-14)
    np.testing.assert_allclose(d, -p / L, rtol=1e-13)
    assert isinstance(law.pressure(1e-6), float)
    assert law.contact_area(2e-6) == pytest.approx(0.2, abs=1e-15)   # linear between nodes
    assert law.length == pytest.approx(L, rel=1e-13)
    assert law.separation_range == (0.0, 3e-6) and law.has_area


def test_sphere_on_exponential_law():
    # nearly rigid sphere (p0/E* = 1e-12): P = 2 pi R p0 l exp(delta/l) to ~1e-10
    law = exponential_law(modulus=E)
    p = egw.Params(radius=R, modulus=E, flat_law=law)
    assert p.model == "flat law" and p.sigma == pytest.approx(L)
    delta = np.array([-2e-6, 0.0, 2e-6])
    r = egw.solve(p, delta)
    exact = 2 * math.pi * R * P0 * L * np.exp(delta / L)
    np.testing.assert_allclose(r.force, exact, rtol=1e-7)
    np.testing.assert_allclose(r.stiffness, exact / L, rtol=1e-6)
    # a scalar overlap (README's egw.solve(p, delta_m).force): floats, the same values
    # (before audit25 every field came back NaN without a word)
    for i, d in enumerate(delta):
        one = egw.solve(p, float(d))
        assert isinstance(one.force, float) and one.force == r.force[i], (one, r.force[i])
        assert one.stiffness == r.stiffness[i] and one.iterations == r.iterations[i]
    t = egw.Table.build(p, -8e-6, 4e-6, 1e-6)
    f, k = t.eval(np.linspace(-30e-6, 4e-6, 35))
    np.testing.assert_allclose(f, 2 * math.pi * R * P0 * L * np.exp(np.linspace(-30e-6, 4e-6,
                                                                          35) / L), rtol=1.2e-6)


def test_bad_input():
    with pytest.raises(egw.InvalidArgumentError, match=r"u\(2\)"):
        egw.FlatLaw.from_table([0.0, 0.0], [2.0, 1.0])
    with pytest.raises(egw.InvalidArgumentError, match=r"p\(2\)"):
        egw.FlatLaw.from_table([0.0, 1.0], [1.0, 2.0])
    with pytest.raises(egw.InvalidArgumentError, match="area"):
        egw.FlatLaw.from_table([0.0, 1.0], [2.0, 1.0], area=[0.5])
    with pytest.raises(TypeError):
        egw.FlatLaw.from_table("abc", [2.0, 1.0])
    law = exponential_law()
    with pytest.raises(egw.EgwError):            # no area data
        law.contact_area(1e-6)
    with pytest.raises(egw.InvalidArgumentError):
        law.pressure(float("nan"))
    with pytest.raises(egw.InvalidArgumentError, match="flat_law"):
        egw.Params(model="GW", flat_law=law)
    with pytest.raises(egw.InvalidArgumentError, match="flat_law"):
        egw.Params(model="flat law")
    law_e = exponential_law(modulus=E)
    with pytest.raises(egw.InvalidArgumentError, match="modulus"):
        egw.solve(egw.Params(radius=R, modulus=2 * E, flat_law=law_e), 0.0)
    # the flow-pressure cap: a law's solve caps the total pressure at p_y (the cap clamps
    # it: p_y to rounding) with less force; its force table refuses the cap naming it, as
    # egw_table_build does (it dropped the cap before stop 59)
    # (on a soft sphere, E* = 1e3 P0: 3e-6 is ~12 delta_y; on the rigid one delta_y is
    # 2.5e-12 and the solve refuses an overlap beyond 1e12 delta_y)
    soft = exponential_law(modulus=1e3 * P0)
    free = egw.solve(egw.Params(radius=R, modulus=1e3 * P0, flat_law=soft), 3e-6)
    p_y = 0.5 * float(free.max_pressure)
    capped = egw.Params(radius=R, modulus=1e3 * P0, flat_law=soft, flow_pressure=p_y)
    res = egw.solve(capped, 3e-6)
    assert abs(float(res.max_pressure) / p_y - 1.0) <= 1e-12
    assert float(res.force) < float(free.force)
    with pytest.raises(egw.InvalidArgumentError, match="flow_pressure"):
        egw.Table.build(capped, -8e-6, 4e-6, 1e-4)


def test_file_round_trip(tmp_path):
    law = exponential_law(area=[0.5, 0.3, 0.1], modulus=E)
    path = tmp_path / "law.csv"
    law.write(path)
    back = egw.FlatLaw.read(path)
    u = np.linspace(-1e-6, 5e-6, 13)
    np.testing.assert_array_equal(back.pressure(u), law.pressure(u))
    assert back.modulus == E and back.has_area
    (tmp_path / "mine.csv").write_text("u,pressure\n0,2\n1e-6,1\n")
    assert egw.FlatLaw.read(tmp_path / "mine.csv").pressure(0.5e-6) < 2
    (tmp_path / "bad.csv").write_text("u,pressure\n0,2\n1e-6,oops\n")
    with pytest.raises(egw.FileError, match="line 3"):
        egw.FlatLaw.read(tmp_path / "bad.csv")


def test_psd_from_heights():
    # one cosine mode along x: the spectrum peaks at its wavenumber 2 pi 4/L
    n, dx, a = 64, 1e-6, 2e-7
    x = np.arange(n) * dx
    z = a * np.cos(2 * np.pi * 4 * x / (n * dx))[None, :] * np.ones((n, 1))
    q, C = egw.flat_law.psd_from_heights(z, dx, per_decade=40)
    k = np.argmax(C)                     # the annulus [q_k, q_k+1] holding the mode
    # (the mode may sit on an annulus' edge, where the step's two nodes are 1e-9 apart)
    assert q[k] <= 2 * np.pi * 4 / (n * dx) <= q[k + 1] * (1 + 1e-8)
    # a band-limited isotropic surface (modes inside the Nyquist circle): the step
    # spectrum's integral 2 pi int q C dq is the map's variance (each annulus keeps its
    # modes' power), to rounding
    rng = np.random.default_rng(7)
    f = np.fft.fft2(rng.normal(size=(128, 128)))
    k = np.hypot(*np.meshgrid(np.fft.fftfreq(128), np.fft.fftfreq(128)))
    f[(k > 0.25) | (k == 0)] = 0
    z = np.real(np.fft.ifft2(f))
    q, C = egw.flat_law.psd_from_heights(z, 1.0)
    annuli = np.pi * (q[1::2] ** 2 - q[0::2] ** 2) * C[0::2]
    assert annuli.sum() == pytest.approx(z.var(), rel=1e-6)
