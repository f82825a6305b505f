"""Keyword-only quantities: a positional call that could swap quantities of one kind
raises a TypeError naming the keywords (the issue's C-order call of psi_from_hardness,
(E*, H, K, sigma, beta), returned psi ~ 4.9e7 without a word)."""
import math

import pytest

import egw

P = egw.Params(model="EP-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0, psi=2.0)


@pytest.mark.parametrize("call, names", [
    (lambda: egw.psi_from_hardness(1e11, 2e9, 0.6, 1e-6, 1e-5),
     ("modulus=", "hardness=", "sigma=", "summit_radius=", "egw_psi_from_hardness")),
    (lambda: egw.psi_from_hardness(1e11, hardness=2e9, sigma=1e-6, summit_radius=1e-5),
     ("modulus=",)),
    (lambda: egw.mu_from_summits(1e10, 1e-5, 1e-6, 5e-4),
     ("summit_density=", "summit_radius=", "sigma=", "radius=")),
    (lambda: egw.restitution(P, 1e-3, 0.1), ("mass=", "velocity=")),
    (lambda: egw.time_step(P, 1e-3, 0.1), ("mass=", "velocity=")),
], ids=["psi C order", "psi first positional", "mu", "restitution", "time_step"])
def test_positional_calls_are_refused_with_the_keywords_named(call, names):
    with pytest.raises(TypeError) as info:
        call()
    for name in names:
        assert name in str(info.value)


def test_keyword_calls_give_the_formulas():
    # psi = 4E*/(3 pi K H) sqrt(sigma/beta), mu = (8/3) eta sigma sqrt(2 R beta)
    # (doc/parameters.md section 3); rounding only: 1e-14
    e, h, k, sigma, beta, eta, r = 1e11, 2e9, 0.6, 1e-6, 1e-5, 1e10, 5e-4
    psi = egw.psi_from_hardness(hardness_coeff=k, summit_radius=beta, sigma=sigma,
                                hardness=h, modulus=e)
    assert psi == pytest.approx(4 * e / (3 * math.pi * k * h) * math.sqrt(sigma / beta),
                                rel=1e-14)
    mu = egw.mu_from_summits(radius=r, sigma=sigma, summit_radius=beta, summit_density=eta)
    assert mu == pytest.approx(8 / 3 * eta * sigma * math.sqrt(2 * r * beta), rel=1e-14)
    # keyword-only in the signature too (what help() and IDEs show)
    import inspect
    sig = inspect.signature(egw.psi_from_hardness)
    assert all(p.kind is p.KEYWORD_ONLY for p in sig.parameters.values())
