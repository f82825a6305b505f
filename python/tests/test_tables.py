"""Tables from Python: values against full solves (the table's contract: rel_tol between
nodes), one C call per array, files, and the range warning."""
import numpy as np
import pytest

import egw

P = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)


@pytest.fixture(scope="module")
def table():
    t = egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-5)
    yield t
    t.close()


def test_table_meets_rel_tol_against_solves(table):
    info = table.info
    assert info.n_nodes > 4 and info.rel_tol == 1e-5
    d = np.linspace(0.0, 2e-5, 7)[1:]
    f, _ = table.eval(d)
    ref = egw.solve(P, d, egw.Options(rel_tol=1e-8)).force
    # interpolation error <= rel_tol (1e-5) + the solves' own 1e-8
    np.testing.assert_allclose(f, ref, rtol=1.1e-5)


def test_array_eval_equals_pointwise_eval(table):
    d = np.linspace(-3e-6, 1.9e-5, 101).reshape(101)
    f, k = table.eval(d)
    for i in range(0, 101, 10):
        fi, ki = table.eval(float(d[i]))
        assert fi == f[i] and ki == k[i]
    info = table.info
    below = info.cutoff * (1 + 1e-9)  # cut-off < 0: just below it
    # below a rough table's cut-off exactly 0 (doc/formats.md rule 1: the force there is
    # under 1e-12 P_ref); at the cut-off itself the first node's force, at most that
    assert table.eval(below) == (0.0, 0.0)
    assert table.eval(2 * info.cutoff) == (0.0, 0.0)
    f_cut, _ = table.eval(info.cutoff)
    assert 0.0 < f_cut <= 1e-12 * info.reference_force


def test_above_range_warns_and_extrapolates(table):
    with pytest.warns(egw.OutOfRangeWarning, match="delta_max"):
        f, k = table.eval([1e-5, 3e-5])
    assert f[1] > f[0]


def test_write_read_roundtrip(table, tmp_path):
    for fmt in ("binary", "csv"):
        path = tmp_path / f"t.{fmt}"
        table.write(path, fmt)
        back = egw.Table.read(path)
        d = np.linspace(0, 2e-5, 33)
        np.testing.assert_allclose(back.eval(d)[0], table.eval(d)[0], rtol=1e-14)


def test_bad_file_and_closed_table(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("not a table\n")
    with pytest.raises(egw.FileError):
        egw.Table.read(bad)
    t = egw.Table.build(egw.Params(model="Hertz", radius=1e-3, modulus=1e9), 0, 1e-5, 1e-4)
    t.close()
    with pytest.raises(ValueError, match="closed"):
        t.eval(1e-6)


def test_universal_slice_matches_universal_eval():
    u = egw.UniversalTable.build(egw.Params(model="E-GW"), 2.0, 8.0, -3.0, 20.0, 1e-4)
    p = P.replace(mu=5.0)
    s = u.slice(p, 1.5e-5)
    d = np.linspace(-1e-6, 1.5e-5, 9)
    # to rounding in contact; in the separated tail (d < 0) the slice's 1-D evaluation
    # takes its resampled pieces, within 5e-2 rel_tol of the same interpolant
    # (doc/formats.md, after rule 4)
    tail = d < 0
    np.testing.assert_allclose(s.eval(d[~tail])[0], u.eval(p, d[~tail])[0], rtol=1e-12,
                               atol=1e-30)
    np.testing.assert_allclose(s.eval(d[tail])[0], u.eval(p, d[tail])[0], rtol=5e-2 * 1e-4)


def test_hysteresis_table_histories():
    # EP-GW (scaled: R = E = sigma = 1, psi = 2): loading moves each contact's state up;
    # below its state a contact follows its unloading curve, under the loading force
    p = egw.Params(model="EP-GW", sigma=1.0, mu=4.0, psi=2.0)
    h = egw.HysteresisTable.build(p, -2.0, 4.0, rel_tol=1e-3)
    state = egw.HysteresisTable.new_state(3)
    f_up, _ = h.eval(np.array([1.0, 2.0, 3.0]), state)
    np.testing.assert_array_equal(state, [1.0, 2.0, 3.0])
    f_down, _ = h.eval(np.array([0.5, 1.5, 2.5]), state)
    np.testing.assert_array_equal(state, [1.0, 2.0, 3.0])  # unloading keeps the history
    load = egw.solve(p, [0.5, 1.5, 2.5]).force
    assert np.all(f_down < load) and np.all(f_down >= 0)


def test_hysteresis_energy():
    # the energy returned below a turning point is the integral of the table's own force
    # (trapezoid rule, 4000 steps from 1 to 3 below m = 3: the force is smooth there,
    # error ~1e-7 relative) to the table's rel_tol of each energy (EP-GW tables interpolate
    # ln(E_load/E): within rel_tol of the energy, doc/theory.md section 8); it grows with
    # the turning point; the states are not changed
    p = egw.Params(model="EP-GW", sigma=1.0, mu=4.0, psi=2.0)
    h = egw.HysteresisTable.build(p, -2.0, 4.0, rel_tol=1e-3)
    x = np.linspace(1.0, 3.0, 4001)
    f, _ = h.eval(x, np.full(x.size, 3.0))
    u = h.energy([1.0, 3.0], 3.0)
    trapezoid = 0.5 * np.sum((f[1:] + f[:-1]) * np.diff(x))
    assert abs((u[1] - u[0]) - trapezoid) <= 1e-3 * (u[0] + u[1])
    state = np.array([3.0, 3.0])
    assert np.all(h.energy([3.5, 3.5], state) > u[1]) and np.all(state == 3.0)


def test_hysteresis_table_files_and_info(tmp_path):
    # written and read back in both formats, a table evaluates exactly like the original
    # (17 digits in CSV, raw bytes in binary); the array call equals one call per contact
    p = egw.Params(model="EP-GW", sigma=1.0, mu=4.0, psi=2.0)
    h = egw.HysteresisTable.build(p, -2.0, 4.0, rel_tol=1e-3)
    info = h.info()
    assert info.model == 3 and not info.reversible and info.n_delta_max >= 4
    assert info.delta_max == 4.0 and info.rel_tol == 1e-3 and info.cutoff < -2.0
    d = np.array([3.5, 1.0, -1.0, 2.0])
    for fmt in ("csv", "binary"):
        path = tmp_path / f"h.{fmt}"
        h.write(path, fmt)
        back = egw.HysteresisTable.read(path)
        s1 = np.full(4, 3.7)
        s2 = s1.copy()
        np.testing.assert_array_equal(h.eval(d, s1)[0], back.eval(d, s2)[0])
        assert back.info() == info
    state = np.full(4, 3.7)
    f_all, k_all = h.eval(d, state)
    for i in range(4):
        s = np.full(1, 3.7)
        f1, k1 = h.eval(d[i:i + 1], s)
        assert f1[0] == f_all[i] and k1[0] == k_all[i]
    bad = tmp_path / "bad.csv"
    bad.write_text((tmp_path / "h.csv").read_text().replace("# loading = -", "# loading = +", 1)
                   .replace("e-0", "e-1", 1))
    with pytest.raises(egw.EgwError, match="checksum"):
        egw.HysteresisTable.read(bad)
    with pytest.raises(egw.EgwError):
        egw.HysteresisTable.read(tmp_path / "missing")


def test_universal_eval_broadcasts_params_in_one_call():
    u = egw.UniversalTable.build(egw.Params(model="E-GW"), 2.0, 8.0, -3.0, 20.0, 1e-3)
    p = P.replace(mu=np.array([3.0, 5.0]), radius=np.array([[1e-4], [5e-4], [1e-3]]))
    d = 2e-6
    f, k = u.eval(p, d)
    assert f.shape == k.shape == (3, 2)
    for i, j in np.ndindex(f.shape):
        q = P.replace(mu=float(p.mu[j]), radius=float(p.radius[i, 0]))
        assert u.eval(q, d) == (f[i, j], k[i, j])
    with pytest.warns(egw.OutOfRangeWarning):
        f, _ = u.eval(P.replace(mu=np.array([5.0, 50.0])), d)
    assert np.isnan(f[1]) and f[0] > 0
    with pytest.raises(egw.InvalidArgumentError, match="index 1: delta"):
        u.eval(P.replace(mu=5.0), [1e-6, float("nan")])
