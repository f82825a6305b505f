import os

import pytest

import egw


def test_python_scene_defaults_are_the_library_defaults():
    assert egw.Scene() == egw.Scene.default()


def test_choose_and_read_example_scene(repo):
    choice = egw.choose(egw.Scene())
    assert choice.kind == "table" and "one parameter set" in choice.reason
    s = egw.Scene.read(os.path.join(repo, "example", "scenes", "glass_beads.nml"))
    s.validate()


def test_scalar_for_a_per_type_list_named():
    # radius, modulus, poisson are lists (one per type): a scalar raised
    # "TypeError: object of type 'float' has no len()", naming nothing
    for name in ("radius", "modulus", "poisson"):
        with pytest.raises(TypeError, match=f"{name} = "):
            egw.choose(egw.Scene(**{name: 1.0}))
