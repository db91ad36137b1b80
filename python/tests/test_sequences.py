"""Any sequence of numbers where the package takes numbers: numpy arrays and scalars, tuples,
pandas Series give what the equal list gives (a numpy array was refused: "the truth value of
an array ... is ambiguous")."""

import numpy as np
import pandas as pd
import pytest

import emnet
from conftest import CANTILEVER


def test_sweep_frequencies_as_numpy_tuple_and_series(fishfin):
    reference = emnet.sweep_switching(fishfin, frequencies=[4.0, 5.0])
    for given in (np.array([4.0, 5.0]), (4, 5), pd.Series([4.0, 5.0]), np.array([4, 5])):
        result = emnet.sweep_switching(fishfin, frequencies=given)
        assert list(result["frequencies_hz"]) == [4.0, 5.0]
        assert list(result["outputs"]["name"]) == list(reference["outputs"]["name"])
        for mine, theirs in zip(result["outputs"]["right"], reference["outputs"]["right"]):
            assert list(mine) == list(theirs)


def test_a_text_or_an_object_is_refused_naming_the_key(fishfin):
    with pytest.raises(emnet.InputError) as error:
        emnet.sweep_switching(fishfin, frequencies="4,5")
    assert error.value.key == "frequencies"
    with pytest.raises(emnet.InputError) as error:
        emnet.sweep_switching(fishfin, frequencies=[4.0, object()])
    assert error.value.key == "frequencies"


def test_study_takes_numpy_frequencies_and_values(cantilever):
    listed = emnet.study(cantilever, vary={"beam.bending_stiffness": [1.0, 2.0]}, threads=1)
    arrays = emnet.study(cantilever, vary={"beam.bending_stiffness": np.array([1.0, 2.0])},
                         threads=1)
    assert listed["f1_hz"].tolist() == arrays["f1_hz"].tolist()


def test_scene_values_may_be_numpy_scalars():
    plain = emnet.Scene(CANTILEVER, set={"beam.segments": 12})
    numpy_set = emnet.Scene(CANTILEVER, set={"beam.segments": np.int64(12)})
    assert list(emnet.modes(plain)["modes"]["frequency_hz"]) == \
        list(emnet.modes(numpy_set)["modes"]["frequency_hz"])


# ---- every numeric keyword of every function: numpy's and pandas' numbers give Python's ------

def same(mine, theirs, path="result"):
    """`mine` equals `theirs` exactly, recursively, but for timings (keys ending in seconds)."""
    if isinstance(theirs, pd.DataFrame):
        pd.testing.assert_frame_equal(mine, theirs, check_exact=True)
    elif isinstance(theirs, dict):
        assert list(mine) == list(theirs), path
        for key in theirs:
            if not key.endswith("seconds"):
                same(mine[key], theirs[key], f"{path}.{key}")
    elif isinstance(theirs, np.ndarray):
        assert mine.shape == theirs.shape and (mine == theirs).all(), path
    elif isinstance(theirs, list):
        assert len(mine) == len(theirs), path
        for k, (a, b) in enumerate(zip(mine, theirs)):
            same(a, b, f"{path}[{k}]")
    else:
        assert type(mine) is type(theirs) and mine == theirs, path


def _series(values):
    return pd.Series(values, index=[f"row{k}" for k in range(len(values))])


# One number where a number is wanted; int64 only for whole values.
SCALAR_KINDS = {
    "numpy float64": np.float64,
    "numpy int64": np.int64,
    "0-d array": np.array,
    "1-element array": lambda value: np.array([value]),
    "1-element Series": lambda value: _series([value]),
    "1-element tuple": lambda value: (value,),
}

SWEEP = {"from_hz": 4, "to_hz": 6, "step_hz": 1}
FIN_AC_REDUCED = {"to_hz": 20, "points": 5, "reduce": True, "band_hz": 20, "tolerance": 1e-3}
FIN_TRAN = {"periods": 0.5, "points_per_period": 10}
FIN_DECK = {"analysis": "tran", "periods": 3, "points_per_period": 100}
GRID = {"vary": {"beam.bending_stiffness": [1.0, 2.0]}, "threads": 1}
DRAWS = {"vary": ["beam.bending_stiffness=uniform(90%,110%)"], "samples": 3, "threads": 1}

# function, scene, the other keyword arguments, the keyword given as numpy/pandas, its value
# (none the default: a value lost on the way would show as a different result).
SCALAR_CASES = [
    ("modes", "fishfin", {"error_estimate": False}, "count", 3),
    ("ac", "cantilever", {"to_hz": 50, "points": 5}, "from_hz", 2),
    ("ac", "cantilever", {"from_hz": 1, "points": 5}, "to_hz", 40),
    ("ac", "cantilever", {"from_hz": 1, "to_hz": 50}, "points", 4),
    ("ac", "fishfin", FIN_AC_REDUCED, "tolerance", 1e-2),
    ("ac", "fishfin", FIN_AC_REDUCED, "band_hz", 30),
    ("tran", "fishfin", FIN_TRAN, "periods", 1),
    ("tran", "fishfin", FIN_TRAN, "switching_hz", 4),
    ("tran", "fishfin", FIN_TRAN, "rtol", 1e-5),
    ("tran", "fishfin", FIN_TRAN, "atol", 1e-12),
    ("tran", "fishfin", FIN_TRAN, "max_step", 0.01),
    ("tran", "fishfin", FIN_TRAN, "points_per_period", 8),
    ("tran", "fishfin", FIN_TRAN, "shape_instants", 2),
    ("sweep_switching", "fishfin", SWEEP, "from_hz", 5),
    ("sweep_switching", "fishfin", SWEEP, "to_hz", 5),
    ("sweep_switching", "fishfin", SWEEP, "step_hz", 2),
    ("sweep_switching", "fishfin", {"frequencies": [5.0]}, "samples", 16),
    ("sweep_switching", "fishfin", {"frequencies": [5.0], "method": "shooting"}, "rtol", 1e-8),
    ("sweep_switching", "fishfin", {"frequencies": [5.0]}, "shape_instants", 2),
    ("identify", "fishfin", {}, "target_hz", 5),
    ("identify", "fishfin", {"target_hz": 40}, "mode", 2),
    ("sensitivity", "fishfin", {"parameters": ["beam.bending_stiffness"]}, "modes", 2),
    ("mismatch", "fishfin", {}, "frequency_hz", 4),
    ("mismatch", "fishfin", {}, "change", 0.1),
    ("netlist", "fishfin", FIN_DECK, "periods", 3),
    ("netlist", "fishfin", FIN_DECK, "points_per_period", 100),
    ("netlist", "fishfin", FIN_DECK, "rtol", 1e-5),
    ("crosscheck", "cantilever", {"analyses": "op"}, "timeout", 30),
    ("study", "cantilever", GRID, "modes", 2),
    ("study", "cantilever", GRID, "threads", 2),
    ("study", "cantilever", DRAWS, "samples", 4),
    ("study", "cantilever", DRAWS, "seed", 5),
    ("variants", "cantilever", DRAWS | {"threads": None}, "samples", 4),
    ("variants", "cantilever", DRAWS | {"threads": None}, "seed", 5),
]


def _call(function, scene, fixed, keyword, value):
    arguments = {k: v for k, v in fixed.items() if v is not None}
    arguments[keyword] = value
    return getattr(emnet, function)(scene, **arguments)


def _scalar_params():
    for case in SCALAR_CASES:
        for kind in SCALAR_KINDS:
            if kind != "numpy int64" or float(case[4]).is_integer():
                yield pytest.param(case, kind, id=f"{case[0]}-{case[3]}-{kind}")


@pytest.mark.parametrize("case, kind", list(_scalar_params()))
def test_numpy_and_pandas_numbers_give_the_plain_result(case, kind, fishfin, cantilever):
    function, scene_name, fixed, keyword, value = case
    scene = {"fishfin": fishfin, "cantilever": cantilever}[scene_name]
    plain = _call(function, scene, fixed, keyword, value)
    given = _call(function, scene, fixed, keyword, SCALAR_KINDS[kind](value))
    same(given, plain)


# Many numbers where a list is wanted.
LIST_KINDS = {
    "list": list,
    "tuple": tuple,
    "numpy array": np.array,
    "numpy int array": lambda values: np.array(values, dtype=np.int64),
    "Series": _series,
}
LIST_CASES = [
    ("sweep_switching", "fishfin", {}, "frequencies", [4, 5, 6]),
    ("study", "fishfin", {"vary": {"beam.bending_stiffness": [1e-3, 2e-3]},
                          "analyses": ["sweep-switching"], "at": [5.0]},
     "sweep_frequencies", [4, 5, 6]),
    ("study", "fishfin", {"vary": {"beam.bending_stiffness": [1e-3, 2e-3]},
                          "analyses": ["sweep-switching"], "sweep_frequencies": [4.0, 5.0]},
     "at", [4, 5]),
]


@pytest.mark.parametrize("case", LIST_CASES, ids=lambda case: f"{case[0]}-{case[3]}")
@pytest.mark.parametrize("kind", sorted(LIST_KINDS))
def test_any_sequence_gives_the_list_result(case, kind, fishfin):
    function, _, fixed, keyword, values = case
    plain = _call(function, fishfin, fixed, keyword, [float(v) for v in values])
    same(_call(function, fishfin, fixed, keyword, LIST_KINDS[kind](values)), plain)


@pytest.mark.parametrize("kind", sorted(LIST_KINDS))
def test_vary_values_as_any_sequence(kind, cantilever):
    plain = emnet.study(cantilever, vary={"beam.bending_stiffness": [1.0, 2.0]}, threads=1)
    given = emnet.study(cantilever, vary={"beam.bending_stiffness": LIST_KINDS[kind]([1, 2])},
                        threads=1)
    same(given, plain)
    assert list(given["beam.bending_stiffness"]) == [1.0, 2.0]


@pytest.mark.parametrize("kind", sorted(SCALAR_KINDS))
def test_with_values_takes_any_number(kind, cantilever):
    changed = cantilever.with_values({"beam.bending_stiffness": SCALAR_KINDS[kind](4)})
    assert changed.get("beam.bending_stiffness") == 4.0
    same(emnet.static(changed), emnet.static(cantilever.with_values({"beam.bending_stiffness": 4})))


def test_with_values_takes_a_series_by_key(cantilever):
    row = pd.Series({"beam.bending_stiffness": np.float64(3.0), "beam.mass_per_length": 0.4})
    changed = cantilever.with_values(row)
    assert changed.get("beam.bending_stiffness") == 3.0
    assert changed.get("beam.mass_per_length") == 0.4


@pytest.mark.parametrize("given", [("tip", "mid"), np.array(["tip", "mid"]),
                                   pd.Series(["tip", "mid"])], ids=["tuple", "array", "Series"])
def test_probe_names_as_any_sequence(given, cantilever):
    same(emnet.static(cantilever, probes=given), emnet.static(cantilever, probes=["tip", "mid"]))


class _InlineClient:
    """A Dask client's face that runs each task at once, here: the study's chunking without a
    cluster (test_dask.py runs a real one)."""

    class _Done:
        def __init__(self, value):
            self.value = value

        def result(self):
            return self.value

    def scheduler_info(self):
        return {"workers": {"one": {}, "two": {}}}

    def map(self, function, *iterables, pure=True):
        return [self._Done(function(*arguments)) for arguments in zip(*iterables)]


@pytest.mark.parametrize("kind", sorted(SCALAR_KINDS))
def test_chunk_size_takes_any_number(kind, cantilever):
    vary = {"beam.bending_stiffness": [1.0, 2.0, 3.0, 4.0, 5.0]}
    local = emnet.study(cantilever, vary=vary, threads=1)
    plain = emnet.study(cantilever, vary=vary, client=_InlineClient(), chunk_size=2)
    given = emnet.study(cantilever, vary=vary, client=_InlineClient(),
                        chunk_size=SCALAR_KINDS[kind](2))
    same(plain, local)
    same(given, plain)
