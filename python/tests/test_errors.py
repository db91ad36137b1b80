"""Errors: bad input raises emnet.InputError (a ValueError) naming file, line and key; a numerical
failure raises emnet.NumericalError with the reason."""

import inspect

import numpy as np
import pandas as pd
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


# ---- Python values the package refuses before the library sees them -------------------------

# Every keyword argument of every function, by what it takes. A new keyword must be added here
# (test_every_keyword_is_listed), so that its refusals are tested too.
KEYWORDS = {
    "static": {"probes": "texts"},
    "modes": {"count": "integer", "dense": "flag", "error_estimate": "flag", "shapes": "flag",
              "probes": "texts"},
    "ac": {"from_hz": "number", "to_hz": "number", "points": "integer", "log": "flag",
           "probes": "texts", "reduce": "flag", "tolerance": "number", "band_hz": "number",
           "method": "text"},
    "tran": {"periods": "number", "switching_hz": "number", "method": "text", "rtol": "number",
             "atol": "number", "max_step": "number", "start": "text",
             "points_per_period": "integer", "outputs": "texts", "shape_instants": "integer"},
    "sweep_switching": {"frequencies": "numbers", "from_hz": "number", "to_hz": "number",
                        "step_hz": "number", "method": "text", "samples": "integer",
                        "rtol": "number", "outputs": "texts", "sources": "texts",
                        "shape_instants": "integer"},
    "identify": {"target_hz": "number", "parameter": "text", "mode": "integer"},
    "sensitivity": {"modes": "integer", "parameters": "texts", "check": "flag"},
    "mismatch": {"frequency_hz": "number", "output": "text", "change": "number"},
    "netlist": {"analysis": "text", "periods": "number", "points_per_period": "integer",
                "rtol": "number", "control": "flag"},
    "crosscheck": {"analyses": "text", "timeout": "number"},
    "study": {"vary": "texts", "samples": "integer", "seed": "integer", "analyses": "texts",
              "modes": "integer", "sweep_frequencies": "numbers", "at": "numbers",
              "threads": "integer", "chunk_size": "integer"},
    "variants": {"vary": "texts", "samples": "integer", "seed": "integer"},
}
# Taken as they are: a Dask client; a CSV file's path or a DataFrame (variants); the study's
# progress (anything: its truth, or a callable the bindings call).
NOT_CONVERTED = {"scene", "client", "variants", "progress"}

# What each kind refuses: a text, an object, a bool for a number, a NaN, an infinity, two
# numbers where one is wanted, a fraction where a whole number is, a number where a text is.
BAD = {
    "number": ["abc", object(), True, float("nan"), float("inf"), [1.0, 2.0], 1j],
    "integer": ["3", object(), True, 2.5, 2**70, np.array([1, 2])],
    "flag": ["yes", 1, object()],
    "text": [3, object(), ["a"]],
    "texts": [3, [1, 2], ["tip", None]],
    "numbers": ["4,5", [4.0, object()], [4.0, float("nan")], [4.0, True], object()],
}


class _NoCluster:
    """A client whose study never starts: chunk_size is refused before any task."""

    def scheduler_info(self):
        return {"workers": {"one": {}}}


# What each function needs besides the keyword under test.
NEEDS = {"identify": {"target_hz": 5.0},
         "study": {"vary": {"beam.bending_stiffness": [1.0, 2.0]}, "client": _NoCluster()}}


def _bad_cases():
    for function, keywords in KEYWORDS.items():
        for keyword, kind in keywords.items():
            for k, value in enumerate(BAD[kind]):
                yield pytest.param(function, keyword, value, id=f"{function}-{keyword}-{k}")


@pytest.mark.parametrize("function, keyword, value", list(_bad_cases()))
def test_a_bad_python_value_names_the_keyword(function, keyword, value, cantilever):
    arguments = dict(NEEDS.get(function, {}))
    if not (function == "study" and keyword == "chunk_size"):
        arguments.pop("client", None)
    arguments[keyword] = value
    with pytest.raises(emnet.InputError) as error:
        getattr(emnet, function)(cantilever, **arguments)
    assert error.value.key == keyword
    assert error.value.where == keyword
    assert str(error.value).startswith(f"{keyword}: key '{keyword}': ")


@pytest.mark.parametrize("function", sorted(KEYWORDS))
def test_every_keyword_is_listed(function):
    parameters = set(inspect.signature(getattr(emnet, function)).parameters)
    assert parameters - NOT_CONVERTED == set(KEYWORDS[function])


@pytest.mark.parametrize("value, words", [
    ("abc", "a number is wanted, got the text 'abc'"),
    (object(), "a number is wanted, got object <object object"),
    (True, "a number is wanted, got bool True"),
    (float("nan"), "a finite number is wanted, got nan"),
    (np.array([1.0, 2.0]), "one number is wanted, got a sequence of 2"),
])
def test_a_bad_number_says_what_it_got(value, words, cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.tran(cantilever, periods=value)
    assert str(error.value).startswith(f"periods: key 'periods': {words}")


def test_a_fraction_for_a_whole_number_is_refused_a_whole_float_taken(cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.modes(cantilever, count=2.5)
    assert "a whole number is wanted, got 2.5" in str(error.value)
    assert list(emnet.modes(cantilever, count=np.float64(2.0)).modes["frequency_hz"]) == \
        list(emnet.modes(cantilever, count=2).modes["frequency_hz"])


def test_a_negative_seed_is_refused_naming_it(cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.variants(cantilever, vary=["beam.bending_stiffness=uniform(90%,110%)"], samples=3,
                       seed=-1)
    assert error.value.key == "seed"
    assert "from 0 to" in str(error.value)


# A numpy value the package converted reaches the library, which words its own refusal with the
# keyword: the values the library checks.
@pytest.mark.parametrize("call, keyword", [
    (lambda s: emnet.crosscheck(s, timeout=np.float64(-1.0)), "timeout"),
    (lambda s: emnet.study(s, vary={"beam.bending_stiffness": [1, 2]}, threads=np.int64(2000)),
     "threads"),
    (lambda s: emnet.tran(s, periods=np.array([-1.0])), "periods"),
    (lambda s: emnet.ac(s, points=pd.Series([0])), "points"),
])
def test_a_converted_value_is_checked_by_the_library(call, keyword, cantilever):
    with pytest.raises(emnet.InputError) as error:
        call(cantilever)
    assert error.value.key == keyword
    assert error.value.where == keyword


@pytest.mark.parametrize("values, key", [
    ({"beam.bending_stiffness": "abc"}, "beam.bending_stiffness"),
    ({"beam.bending_stiffness": object()}, "beam.bending_stiffness"),
    ({"beam.bending_stiffness": [1.0, 2.0]}, "beam.bending_stiffness"),
    ({3: 1.0}, "values"),
    ([1.0], "values"),
])
def test_with_values_refuses_a_non_number_naming_the_key(values, key, cantilever):
    with pytest.raises(emnet.InputError) as error:
        cantilever.with_values(values)
    assert error.value.key == key
    assert error.value.where == "values"


def test_a_vary_value_names_its_scene_key(cantilever):
    with pytest.raises(emnet.InputError) as error:
        emnet.study(cantilever, vary={"beam.bending_stiffness": [1.0, "2"]})
    assert error.value.key == "beam.bending_stiffness"
    assert error.value.where == "vary"


def test_a_key_that_is_not_a_text_is_refused(cantilever):
    with pytest.raises(emnet.InputError) as error:
        cantilever.get(3)
    assert error.value.key == "key"
