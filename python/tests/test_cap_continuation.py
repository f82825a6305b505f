"""The fully capped continuation of the smooth sphere with the cap (doc/theory.md section 12,
"Beyond a table"), which LAMMPS's pair_style egw takes beyond its Hertz + cap table's 1000
delta_y (integrations/lammps/egw_law.h, cap_continue), against egw's cap solves: loading
P = 2 alpha^2 with delta = alpha^2/2 + 8 alpha/pi^2 (R = E* = 1, p_y = 2/pi: delta_y = a_y =
1), and the unloading from delta_m the curve from X scaled by r = alpha(delta_m)/alpha(X):
P(delta) = r^2 P_X(X - (delta_m - delta)/r), dP/ddelta = r P_X'."""
import math

import numpy as np
import pytest

import egw

PY = 2.0 / math.pi
K = 8.0 / math.pi**2
X = 1000.0    # the LAMMPS table's reach, delta_y


def alpha(d):
    return math.sqrt(K * K + 2.0 * d) - K


def capped():
    return egw.Params(model="Hertz", radius=1.0, modulus=1.0, flow_pressure=PY)


@pytest.mark.parametrize("dm", [1500.0, 5000.0])
def test_loading_closed_form(dm):
    # the solver's fully capped limit; 1e-12: rounding of P ~ 1e4 through two formulas
    res = egw.solve(capped(), dm)
    a = alpha(dm)
    assert abs(float(res.force) - 2 * a * a) <= 1e-12 * 2 * a * a
    assert abs(float(res.stiffness) - 4 * a / (a + K)) <= 1e-12 * 4


@pytest.mark.parametrize("dm", [2000.0, 5000.0])
def test_unloading_scales_from_the_table_end(dm):
    # the solves from dm at s = (dm - delta)/(4 alpha_m/pi) from just below the turning
    # point to near the residual overlap, against the X curve's at the same s scaled.
    # Both are the cap solver's (64-ring meshes); the law is exact where the contact is
    # fully capped (edge ring < 1e-7 a from 32 delta_y), so they agree to rounding: 1e-12
    # of P_m (measured 8e-15 and 3e-14), far inside the 1e-3 of LAMMPS's table. Off by
    # the law's error, e.g. r^2 -> r^2 (1 + 1e-6), it fails.
    r = alpha(dm) / alpha(X)
    s = np.array([1e-9, 0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95])
    delta = dm - s * 4 * alpha(dm) / math.pi
    big = egw.solve_unload(capped(), delta, dm)
    small = egw.solve_unload(capped(), X - (dm - delta) / r, X)
    p_m = 2 * alpha(dm) ** 2
    assert np.max(np.abs(np.asarray(big.force) - r * r * np.asarray(small.force))) <= 1e-12 * p_m
    s_big = np.asarray(big.stiffness)
    assert np.max(np.abs(s_big - r * np.asarray(small.stiffness))) <= 1e-12 * np.max(s_big)
    assert np.asarray(big.force)[-1] < 0.02 * p_m    # the curve reaches near separation


@pytest.fixture(scope="module")
def table_to_40():
    # a Hertz + cap table past the full-cap reach (35 delta_y) at 1e-3 (~1 s)
    return egw.HysteresisTable.build(capped(), 0.0, 40.0, 1e-3)


@pytest.mark.parametrize("k", [2.0, 5.0, 20.0])
def test_table_continues_beyond_its_top(table_to_40, k):
    # the library continues the table beyond its delta_max X (stop 64; egw_hysteresis_eval
    # through egw_hysteresis_eval_array, and egw_hysteresis_energy): loading to k X from a
    # new contact and unloading below it, no OutOfRangeWarning (an error here), the force
    # within the table's 1e-3 of max(P, 1e-3 P_m) of egw's cap solves and the energy of
    # its own force's integral (trapezoid on 4000 points, ~1e-6 of U_m). Before stop 64:
    # the warning, and 0.17 of the force too high at 2 X on loading.
    import warnings
    X = table_to_40.info().delta_max
    dm = k * X
    p_m = 2 * alpha(dm) ** 2
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        st = table_to_40.new_state(1)
        f, s = table_to_40.eval(np.array([dm]), st)
        assert st[0] == dm and abs(f[0] - p_m) <= 1e-12 * p_m
        d = dm - np.array([1e-6, 0.05, 0.3, 0.6, 0.9, 0.97]) * 4 * alpha(dm) / math.pi
        st = np.full(d.shape, dm)
        f, s = table_to_40.eval(d, st)
        ref = np.asarray(egw.solve_unload(capped(), d, dm).force)
        assert np.all(st == dm)
        assert np.max(np.abs(f - ref) / np.maximum(ref, 1e-3 * p_m)) <= 1e-3
        # the energy returned from d[2] on: the integral of the table's force below it
        x = np.linspace(dm - 1.05 * 4 * alpha(dm) / math.pi, d[2], 4001)
        fx, _ = table_to_40.eval(x, np.full(x.shape, dm))
        quad = float(np.sum(0.5 * (fx[1:] + fx[:-1]) * np.diff(x)))
        u = table_to_40.energy(d[2], dm)
        u_m = table_to_40.energy(dm, dm)
        assert abs(float(u) - quad) <= 1e-5 * float(u_m)
