import os

import egw


def test_python_scene_defaults_are_the_library_defaults():
    assert egw.Scene() == egw.Scene.default()


def test_choose_and_read_example_scene(repo):
    choice = egw.choose(egw.Scene())
    assert choice.kind == "table" and "one parameter set" in choice.reason
    s = egw.Scene.read(os.path.join(repo, "example", "scenes", "glass_beads.nml"))
    s.validate()
