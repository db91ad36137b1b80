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
