"""Errors: bad input raises emnet.InputError (a ValueError) naming file, line and key; a numerical
failure raises emnet.NumericalError with the reason."""

import pytest

import emnet
from conftest import CANTILEVER


def test_missing_file_names_it():
    with pytest.raises(emnet.InputError) as error:
        emnet.Scene("/nonexistent/scene.toml")
    assert isinstance(error.value, ValueError)
    assert "/nonexistent/scene.toml" in str(error.value)


def test_syntax_error_names_the_line():
    text = "[scene]\nname = \"x\"\n[beam]\nlength = = 3\n"
    with pytest.raises(emnet.InputError) as error:
        emnet.Scene.from_text(text, name="broken.toml")
    assert "broken.toml:4" in str(error.value)


def test_out_of_range_value_names_the_key(cantilever):
    with pytest.raises(emnet.InputError) as error:
        cantilever.with_values({"beam.bending_stiffness": -1.0})
    assert error.value.key == "beam.bending_stiffness"
    assert "> 0" in str(error.value)


def test_unknown_override_names_the_key():
    with pytest.raises(emnet.InputError) as error:
        emnet.Scene(CANTILEVER, set={"beam.lenght": "0.2 m"})
    assert "beam.lenght" in str(error.value)
    assert error.value.where == "set"
    assert str(error.value).startswith("set: key 'beam.lenght': unknown key")


def test_bad_option_names_it(cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.tran(cantilever, periods=-1)
    assert error.value.key == "periods"
    assert error.value.where == "periods"


# An option the library refuses names the keyword argument, not the command line's flag nor
# the library's field where the two differ.
@pytest.mark.parametrize("call, where, key, words", [
    (lambda s: emnet.sweep_switching(s, samples=4), "samples", "samples", "from 8 to 1000000"),
    (lambda s: emnet.sweep_switching(s, step_hz=0), "from_hz/to_hz/step_hz", "step_hz",
     "need 0 < from <= to"),
    (lambda s: emnet.sweep_switching(s, outputs=["deflection@2m"]), "outputs", "deflection@2m",
     "position outside the beam"),
    (lambda s: emnet.static(s, probes=["deflection@2m"]), "probes", "deflection@2m",
     "position outside the beam"),
    (lambda s: emnet.identify(s, 6.0, mode=0), "mode", "mode", ">= 1"),
    (lambda s: emnet.study(s, vary={"beam.bending_stiffness": "uniform(90%,110%)"}), "samples",
     "samples", "needs samples N"),
    (lambda s: emnet.study(s, vary={"beam.bending_stiffness": [1, 2]}, threads=2000), "threads",
     "threads", "from 1 to 1024"),
    (lambda s: emnet.study(s, vary={"beam.bending_stiffness": [1, 2]}, modes=0), "modes",
     "modes", "from 1 to 100"),
])
def test_library_option_errors_name_the_keyword(cantilever, call, where, key, words):
    with pytest.raises(emnet.InputError) as error:
        call(cantilever)
    assert error.value.where == where
    assert error.value.key == key
    assert words in str(error.value)
    assert "--" not in str(error.value)


def test_free_body_has_no_static_state():
    # A free-free beam under a load has no static state: solve_static's operator is singular.
    scene = emnet.Scene(CANTILEVER, set={"beam.left": "free"})
    with pytest.raises(emnet.NumericalError) as error:
        emnet.static(scene)
    assert "static" in str(error.value)
    assert isinstance(error.value, RuntimeError)


def test_dict_scene_with_a_bad_value_type():
    with pytest.raises(emnet.InputError):
        emnet.Scene.from_dict({"beam": {"length": object()}})
