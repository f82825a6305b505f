"""egw.set_progress (issue 32): the callback hears a long call on this thread, done in
[0, 1] and never decreasing (0 first, 1 last), with the C library's stage names; None
switches it off. An EP-GW restitution (sigma 1, psi 2: a loading curve, a history and an
unloading integral, ~0.1 s) is the long call. Fails on main: no set_progress."""
import threading

import pytest

import egw


def _epgw():
    return egw.Params(model="EP-GW", sigma=1.0, mu=4.0, psi=2.0, hardness_coeff=0.6)


def test_progress_reports_a_restitution():
    seen = []
    egw.set_progress(lambda done, stage: seen.append((done, stage)))
    try:
        e = egw.restitution(_epgw(), mass=1.0, velocity=1.0,
                            options=egw.Options(rel_tol=1e-5)).e
    finally:
        egw.set_progress(None)
    assert 0.0 < e < 1.0
    dones = [d for d, _ in seen]
    assert len(dones) >= 4
    assert dones[0] == 0.0 and dones[-1] == 1.0
    assert all(0.0 <= d <= 1.0 for d in dones)
    assert all(b >= a for a, b in zip(dones, dones[1:]))
    stages = {s for _, s in seen}
    assert "history" in stages and "restitution: unloading" in stages


def test_none_switches_progress_off():
    seen = []
    egw.set_progress(lambda done, stage: seen.append(done))
    egw.set_progress(None)
    egw.restitution(_epgw(), mass=1.0, velocity=1.0, options=egw.Options(rel_tol=1e-5))
    assert seen == []


def test_progress_is_per_thread():
    seen = []
    egw.set_progress(lambda done, stage: seen.append(done))
    try:
        worker = threading.Thread(target=lambda: egw.restitution(
            _epgw(), mass=1.0, velocity=1.0, options=egw.Options(rel_tol=1e-5)))
        worker.start()
        worker.join()
    finally:
        egw.set_progress(None)
    assert seen == []   # the hook was set on this thread, the call made on another


def test_bad_callback_is_refused():
    with pytest.raises(TypeError, match="callback"):
        egw.set_progress(3)


def test_callback_replaced_from_inside_itself():
    # a callback that hands over to another on its second report: the new one hears the
    # rest of the same restitution, never decreasing, ending at 1 (on main each nested
    # call of the rest started again at 0); the replaced callback's C thunk is kept alive
    # while it runs (no crash on return into it)
    first, second = [], []

    def hand_over(done, stage):
        first.append(done)
        if len(first) == 2:
            egw.set_progress(lambda d, s: second.append(d))

    egw.set_progress(hand_over)
    try:
        e = egw.restitution(_epgw(), mass=1.0, velocity=1.0,
                            options=egw.Options(rel_tol=1e-5)).e
    finally:
        egw.set_progress(None)
    assert 0.0 < e < 1.0
    assert len(first) == 2 and len(second) >= 2
    assert all(b >= a for a, b in zip(second, second[1:]))
    assert second[-1] == 1.0
