"""Every public function and method has a NumPy-style docstring (numpydoc: Parameters, Returns),
documenting each of its parameters, a frequency's unit in brackets."""

import inspect

import pytest

import emnet

FUNCTIONS = [name for name in emnet.__all__
             if inspect.isfunction(getattr(emnet, name, None))]
METHODS = [f"{cls.__name__}.{name}" for cls in (emnet.Scene, emnet.Result)
           for name, member in vars(cls).items()
           if not name.startswith("_") and isinstance(member, (classmethod, type(lambda: 0)))]


def _documented(doc):
    """{parameter: its description} from a docstring's Parameters section ("a, b : float")."""
    documented, current = {}, []
    for line in doc.split("Parameters\n----------\n", 1)[1].splitlines():
        if line in ("Returns", "Raises"):
            break
        if line and not line.startswith(" "):
            current = [name.strip() for name in line.split(" : ")[0].split(",")]
            documented.update({name: "" for name in current})
        else:
            for name in current:
                documented[name] += line + "\n"
    return documented


def _object(name):
    target = emnet
    for part in name.split("."):
        target = getattr(target, part)
    return target


@pytest.mark.parametrize("name", FUNCTIONS + METHODS)
def test_numpy_style_docstring(name):
    function = _object(name)
    doc = inspect.getdoc(function)
    assert doc and "\nReturns\n-------\n" in doc, name
    parameters = [p for p in inspect.signature(function).parameters
                  if p not in ("self", "cls") and not p.startswith("_")]
    if parameters:
        documented = _documented(doc)
        assert set(parameters) <= set(documented), f"{name}: {documented}"
        for parameter in parameters:
            if parameter.endswith("_hz"):
                assert "[Hz]" in documented[parameter], f"{name}: {parameter}"


def test_the_functions_and_methods_are_found():
    assert {"static", "sweep_switching", "study", "variants"} <= set(FUNCTIONS)
    assert {"Scene.with_values", "Scene.from_dict", "Result.to_frame", "Result.row"} <= \
        set(METHODS)
