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
    assert error.value.where == "--set"


def test_bad_option_names_it(cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.tran(cantilever, periods=-1)
    assert error.value.key == "periods"


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
