"""Python that cannot go wrong silently: masked arrays are refused (never a mask dropped,
never values under a mask computed), and error messages stay short whatever the input
(a message never prints a whole array)."""

import numpy as np
import pytest

import egw
from egw import topography as topo

P = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)
MASKED = np.ma.masked_array([0.0, 1e-6, 2e-6], mask=[False, True, False])


@pytest.mark.parametrize("call", [
    lambda x: egw.hertz(P, x),
    lambda x: egw.solve(P, x),
    lambda x: egw.flat_pressure(P, x),
    lambda x: egw.gauss_integral(1.5, x),
    lambda x: egw.mu_from_summits(summit_density=x, summit_radius=1e-5, sigma=1e-6,
                                  radius=1e-3),
    lambda x: egw.effective_modulus(x + 1e9, 0.3),
    lambda x: egw.Params(model="E-GW", radius=x + 1e-3, modulus=1e9, sigma=1e-6, mu=4.0),
    lambda x: egw.restitution(P, mass=1e-3, velocity=x + 0.1),
], ids=["hertz", "solve", "flat_pressure", "gauss_integral", "mu_from_summits",
        "effective_modulus", "Params", "restitution"])
def test_masked_arrays_are_refused_with_a_clear_message(call):
    with pytest.raises(TypeError, match="masked array with 1 masked value: "):
        call(MASKED)


def test_masked_array_with_nothing_masked_is_its_values():
    # no value hidden: the data are the input (nothing to drop)
    x = np.ma.masked_array([1e-6, 2e-6])
    assert np.array_equal(egw.hertz(P, x)[0], egw.hertz(P, x.data)[0])


def test_masked_table_input_and_height_map_are_refused():
    t = egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4)
    with pytest.raises(TypeError, match="masked"):
        t.eval(MASKED)
    z = np.ma.masked_array(np.random.default_rng(1).standard_normal((16, 16)))
    z[3, 4] = np.ma.masked
    with pytest.raises(ValueError, match="1 masked pixel: "):
        topo.height_map(z, 1.0, "um")


LONG = [str(x) for x in np.linspace(0, 1, 1000)]   # 1000 strings: a TypeError


@pytest.mark.parametrize("call", [
    lambda: egw.hertz(P, LONG),
    lambda: egw.solve(P, np.array(LONG)),
    lambda: egw.Params(model="E-GW", radius=np.array(LONG), modulus=1e9, sigma=1e-6, mu=4),
    lambda: egw.mu_from_summits(summit_density=LONG, summit_radius=1e-5, sigma=1e-6,
                                radius=1e-3),
    lambda: egw.effective_modulus(-np.ones(1000), 0.3),
    lambda: egw.effective_modulus(1e9, np.full(1000, 0.7)),
    lambda: egw.hertz(P, np.full((1000, 1000), 1e-6).astype(complex)[:3]),
], ids=["list", "array", "Params", "mu_from_summits", "E1", "nu1", "complex"])
def test_error_messages_for_1000_point_inputs_are_short(call):
    # the issue saw 17 826 characters; a message names the argument, the shape and a few
    # values: 300 characters hold that with room to spare
    with pytest.raises((TypeError, ValueError)) as info:
        call()
    assert len(str(info.value)) < 300, str(info.value)


def test_short_message_still_names_the_argument_and_shape():
    with pytest.raises(TypeError) as info:
        egw.hertz(P, LONG)
    text = str(info.value)
    assert "delta" in text and "(1000,)" in text and "'0.0'" in text


WORD = "X" * 1000                            # a 1000-character word where a name is asked
NUMBERS = np.arange(1000.0)                  # an array where a word or a callable is asked


def _map():
    return topo.height_map(np.random.default_rng(1).standard_normal((32, 32)), 1.0, "um")


@pytest.mark.parametrize("name, call", [
    ("model", lambda: egw.Params(model=WORD)),
    ("model", lambda: egw.Params(model=NUMBERS)),
    ("model", lambda: egw.Scene(model=WORD).validate()),
    ("radius", lambda: egw.Scene(radius=WORD).validate()),
    ("format", lambda: egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4).write("x.egwt", WORD)),
    ("callback", lambda: egw.set_progress(NUMBERS)),
    ("failed", lambda: egw.errstate(failed=WORD).__enter__()),
    ("unit", lambda: topo.height_map(np.ones((8, 8)), 1.0, WORD)),
    ("mode", lambda: topo.detrend(_map(), mode=WORD)),
    ("method", lambda: topo.spectral_moments(_map(), method=WORD)),
    ("model", lambda: egw.contact_from_topography(_map(), radius=5e-4, E1=70e9, nu1=0.22,
                                                  model=WORD)),
    ("estimate", lambda: egw.contact_from_topography(_map(), radius=5e-4, E1=70e9, nu1=0.22,
                                                     model="E-GW", estimate=WORD)),
], ids=["Params model word", "Params model array", "Scene model", "Scene radius",
        "Table.write format", "set_progress", "errstate", "height_map unit", "detrend mode",
        "spectral_moments method", "contact_from_topography model",
        "contact_from_topography estimate"])
def test_messages_naming_a_word_or_object_stay_short(name, call, tmp_path, monkeypatch):
    # messages that quote a model name, a format, a unit or a callback quoted the whole
    # value before audit33 (1036-6714 characters for these inputs): python/README.md says
    # a message shows a value in at most ~60 characters; 300 hold the name, the value's
    # head and the valid choices
    monkeypatch.chdir(tmp_path)
    with pytest.raises((TypeError, ValueError)) as info:
        call()
    text = str(info.value)
    assert len(text) < 300 and text.startswith(name), text


def test_ignored_psi_warning_is_short():
    with pytest.warns(egw.IgnoredParameterWarning) as rec:
        egw.Params(model="E-GW", radius=1e-3, modulus=1e9, sigma=1e-6, mu=4.0,
                   psi=np.full(1000, 2.0))
    assert len(str(rec[0].message)) < 300


def test_table_evaluators_name_delta_in_their_messages():
    # Table.eval, HysteresisTable.eval and .energy read delta through the same helper as
    # the functions: before audit22 their messages said "value" instead of naming delta
    t = egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4)
    h = egw.HysteresisTable.build(P.replace(model="EP-GW", psi=1.0), -2e-6, 2e-5,
                                  rel_tol=1e-3)
    calls = [lambda: t.eval(MASKED), lambda: t.eval(LONG),
             lambda: h.eval(MASKED, h.new_state(3)), lambda: h.energy(LONG, 1e-6)]
    for call in calls:
        with pytest.raises(TypeError) as info:
            call()
        assert str(info.value).startswith("delta"), str(info.value)


@pytest.mark.parametrize("field, value", [
    ("n_radial", 16.5), ("max_iter", 2.7), ("n_threads", 1.5), ("method", 1.7),
    ("n_radial", "16"), ("rel_tol", "x"), ("rel_tol", None), ("n_threads", True),
    ("rel_tol", np.array([1e-6, 1e-5])),
])
def test_options_of_a_wrong_type_are_refused_naming_the_field(field, value):
    # before audit22 Options(n_radial=16.5) ran with 16 (int() truncated it silently),
    # method=1.7 with Newton, and rel_tol="x" raised numpy's "could not convert string
    # to float" naming nothing
    with pytest.raises(TypeError) as info:
        egw.solve(P, 1e-6, options=egw.Options(**{field: value}))
    assert str(info.value).startswith(field), str(info.value)


def test_options_integral_floats_are_their_integers():
    # a float that is a whole number is that integer (numpy scalars alike)
    o = egw.Options(n_radial=64.0, max_iter=np.int64(50), n_threads=1.0)
    a = egw.solve(P, 1e-6, options=o).force
    b = egw.solve(P, 1e-6, options=egw.Options(n_radial=64, max_iter=50, n_threads=1)).force
    assert a == b


def test_time_step_takes_one_tolerance_and_says_so():
    # egw_time_step_array takes one tolerance for the call; an array of them raised
    # numpy's "only 0-dimensional arrays can be converted" before audit22
    with pytest.raises(TypeError) as info:
        egw.time_step(P, mass=1e-3, velocity=1.0, tolerance=[1e-3, 1e-4])
    assert str(info.value).startswith("tolerance"), str(info.value)


@pytest.mark.parametrize("tolerance", [0.0, float("nan"), 0.2])
def test_time_step_bad_tolerance_raises_even_under_errstate_nan(tolerance):
    # one tolerance for the call: refused like a shared parameter, never NaN per point
    # (before audit25, under errstate(failed="nan") every point came back NaN silently)
    smooth = egw.Params(model="Hertz", radius=1e-3, modulus=1e11)
    with egw.errstate(failed="nan"):
        with pytest.raises(egw.InvalidArgumentError) as info:
            egw.time_step(smooth, mass=[1e-5, 1e-5], velocity=1.0, tolerance=tolerance)
    assert "tolerance" in str(info.value), str(info.value)


@pytest.mark.parametrize("field, value", [
    ("model", 2.5), ("tol", "x"), ("delta_in_sigma", 0.5), ("mu", None), ("radius", ["1e-3"]),
])
def test_scene_fields_of_a_wrong_type_are_refused_naming_the_field(field, value):
    # before audit22 model=2.5 chose for E-GW (int() truncated it), delta_in_sigma=0.5 read
    # as True, tol="x" raised numpy's "could not convert string to float"
    with pytest.raises(TypeError) as info:
        egw.choose(egw.Scene(**{field: value}))
    assert str(info.value).startswith(field), str(info.value)


def test_build_arguments_of_a_wrong_type_name_themselves():
    # float() raised "could not convert string to float: 'x'" without the argument's name
    # before audit22, or read a one-element array as its value
    calls = {"rel_tol": lambda: egw.Table.build(P, -2e-6, 2e-5, rel_tol="x"),
             "delta_max": lambda: egw.HysteresisTable.build(P, -2e-6, [2e-5, 3e-5]),
             "mu_min": lambda: egw.UniversalTable.build(P, None, 8.0, -2, 20),
             "hardness": lambda: egw.psi_from_hardness(modulus=1e11, hardness="2e9",
                                                       sigma=1e-6, summit_radius=1e-5)}
    for name, call in calls.items():
        with pytest.raises(TypeError) as info:
            call()
        assert str(info.value).startswith(name), str(info.value)


@pytest.mark.parametrize("pixel_size", [True, "0.5", (1.0, 2.0, 3.0), [1.0, [2.0, 3.0]]])
def test_a_pixel_size_that_is_not_one_or_two_numbers_is_refused_naming_it(pixel_size):
    # before audit33 True was read as a pixel of 1 (a map silently in the wrong scale),
    # and the others raised Python's "too many values to unpack" or "'>' not supported",
    # naming nothing
    z = np.random.default_rng(2).standard_normal((16, 16))
    with pytest.raises(ValueError) as info:
        topo.height_map(z, pixel_size, "um")
    assert str(info.value).startswith("pixel_size = "), str(info.value)


def test_pixel_sizes_as_numpy_numbers_are_their_values():
    z = np.random.default_rng(2).standard_normal((16, 16))
    a = topo.height_map(z, 0.5, "um")
    for size in (np.array(0.5), np.float32(0.5), (0.5, 0.5), np.array([0.5, 0.5])):
        b = topo.height_map(z, size, "um")
        assert (b.dx, b.dy) == (a.dx, a.dy)


@pytest.mark.parametrize("factor", [2.7, True, "2", float("nan"), float("inf")])
def test_coarse_grain_takes_a_whole_factor_only(factor):
    # before audit33 int() truncated 2.7 to 2 without a word (and took True as 1)
    surface = topo.height_map(np.random.default_rng(3).standard_normal((32, 32)), 1.0, "um")
    with pytest.raises(ValueError) as info:
        topo.coarse_grain(surface, factor)
    assert str(info.value).startswith("factor = "), str(info.value)
    assert np.array_equal(topo.coarse_grain(surface, 2.0).heights,
                          topo.coarse_grain(surface, 2).heights)


def _table():
    return egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4)


@pytest.mark.parametrize("name, call", [
    ("delta", lambda: _table().eval_all(True)),
    ("delta", lambda: _table().eval_all("1e-6")),
    ("delta", lambda: egw.profile(P, True, np.linspace(0, 1e-4, 5))),
    ("delta", lambda: egw.profile(P, np.array([1e-6, 2e-6]), np.linspace(0, 1e-4, 5))),
    ("format", lambda: _table().write("t.bin", 1.5)),
    ("format", lambda: _table().write("t.bin", True)),
    ("radius", lambda: egw.contact_from_topography(
        np.random.default_rng(1).standard_normal((32, 32)), radius=True, E1=70e9, nu1=0.22,
        pixel_size=0.5, unit="um", model="E-GW")),
    ("length", lambda: egw.FlatLaw.from_table([0.0, 1.0], [2.0, 1.0], length="1")),
], ids=["eval_all True", "eval_all str", "profile True", "profile array",
        "write format 1.5", "write format True", "contact_from_topography radius",
        "FlatLaw length"])
def test_one_number_arguments_refuse_booleans_words_and_fractions(name, call, tmp_path,
                                                                 monkeypatch):
    # before audit33 these went through float() or int(): True was an overlap of 1 (or a
    # radius of 1, the binary format), "1e-6" a number, format 1.5 binary, all silently
    monkeypatch.chdir(tmp_path)
    with pytest.raises(TypeError) as info:
        call()
    assert str(info.value).startswith(name), str(info.value)


@pytest.mark.parametrize("radius, modulus, poisson", [
    ([1e-3, 2e-3], [70e9, 200e9], [0.22]),          # type 2's nu left out: was nu = 0
    ([1e-3], [70e9, 200e9], [0.22, 0.3]),           # a type beyond the radii: was unused
])
def test_scene_materials_must_match_the_types(radius, modulus, poisson):
    scene = egw.Scene(radius=radius, modulus=modulus, poisson=poisson, effective_modulus=0.0)
    with pytest.raises(egw.InvalidArgumentError) as info:
        scene.validate()
    assert str(info.value).startswith("modulus, poisson: "), str(info.value)


def test_scene_types_left_out_of_both_lists_take_type_1s_material():
    # egw_scene's documented rule, kept: modulus 0 for a type >= 2 is type 1's material
    one = egw.choose(egw.Scene(radius=[1e-3, 2e-3], modulus=[70e9], poisson=[0.22]))
    both = egw.choose(egw.Scene(radius=[1e-3, 2e-3], modulus=[70e9, 70e9],
                                poisson=[0.22, 0.22]))
    assert one.hertz_error == both.hertz_error
    # with effective_modulus the lists are unused and not checked
    egw.Scene(radius=[1e-3, 2e-3], modulus=[70e9, 1e9, 2e9], poisson=[0.22],
              effective_modulus=3e10).validate()


@pytest.mark.parametrize("heights", [np.ones((8, 8), bool), np.full((8, 8), "1.0"),
                                     np.ones((8, 8), complex)], ids=["bool", "str", "complex"])
def test_height_maps_of_other_than_real_numbers_are_refused(heights):
    # before audit33 float64 conversion read True as 1, "1.0" as 1 and dropped the
    # imaginary part (numpy's ComplexWarning at most)
    with pytest.raises(ValueError, match="heights must be real numbers"):
        topo.height_map(heights, 1.0, "um")
    topo.height_map(np.arange(64).reshape(8, 8) % 5, 1.0, "um")   # integers are numbers


@pytest.mark.parametrize("shape", [2.5, True, -1, (2, 1.5), "3"])
def test_new_state_names_a_bad_shape(shape):
    # before audit33 numpy's own messages ("expected a sequence of integers", "negative
    # dimensions are not allowed") named nothing
    with pytest.raises(ValueError if shape == -1 else TypeError) as info:
        egw.HysteresisTable.new_state(shape)
    assert str(info.value).startswith("shape = "), str(info.value)
    assert egw.HysteresisTable.new_state((2, np.int64(3))).shape == (2, 3)
    assert egw.HysteresisTable.new_state().shape == ()


@pytest.mark.parametrize("call", [
    lambda v: egw.gauss_integral(1.0, 0.5, derivative=v),
    lambda v: egw.flat_pressure(P, 1e-6, derivative=v),
    lambda v: egw.flat_pressure_unload(P, 1e-6, 5e-7, derivative=v),
    lambda v: topo.height_map(np.random.default_rng(4).standard_normal((16, 16)), 1.0, "um",
                              periodic=v),
    lambda v: topo.summit_statistics(
        topo.height_map(np.random.default_rng(4).standard_normal((16, 16)), 1.0, "um"), v),
], ids=["gauss_integral", "flat_pressure", "flat_pressure_unload", "height_map",
        "summit_statistics"])
def test_yes_no_arguments_take_true_or_false_only(call):
    # before audit33 bool() read derivative="no" or periodic="no" (or 0.5) as True: a
    # derivative returned, a map made periodic (FFT derivatives), without a word
    for bad in ("no", 0.5, np.array([True, False])):
        with pytest.raises(TypeError) as info:
            call(bad)
        assert str(info.value).split(" = ")[0] in ("derivative", "periodic"), str(info.value)
    for good in (False, np.bool_(True), 0, 1):
        call(good)
